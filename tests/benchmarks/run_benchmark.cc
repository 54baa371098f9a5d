// `idbench run` without rendering, in process: simulate 2000 steps, identify,
// format the tables, results.json and log.csv (disk writes excluded; the whole
// command including them is timed with hyperfine in BENCHMARKS.md).
#include <benchmark/benchmark.h>

#include "idbench/engine/paper6r.h"
#include "idbench/logs/simulation_log_csv.h"
#include "idbench/workbench/commands/run_command.h"

namespace idbench {
namespace {

void BM_RunDefault(benchmark::State& state) {
  const RobotModel model = MakePaper6r();
  RunOptions options;
  for (auto _ : state) {
    const RunReport report = RunExperiment(model, options);
    const std::string tables = FormatRunTables(options, report);
    const std::string json = FormatRunResultsJson(options, report);
    const std::string csv = FormatLogCsv(model, report.log);
    benchmark::DoNotOptimize(tables.size() + json.size() + csv.size());
  }
}
BENCHMARK(BM_RunDefault)->Unit(benchmark::kMillisecond);

void BM_RunIdentifyOnly(benchmark::State& state) {
  const RobotModel model = MakePaper6r();
  RunOptions options;
  const RunReport report = RunExperiment(model, options);
  for (auto _ : state) {
    benchmark::DoNotOptimize(IdentifyPerBody(model, report.log, report.sample_steps).max_rel_error);
  }
}
BENCHMARK(BM_RunIdentifyOnly)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace idbench

BENCHMARK_MAIN();
