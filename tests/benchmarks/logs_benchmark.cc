// Reading joint logs: the CSV parse rate, whole (ReadRecordedJointLog) and
// streamed (OpenJointLog, chunks discarded), on a 1.2 M-sample, 19-column
// puma560 log (t, q, qd, tau; 20 min at 1 kHz) written once to
// $TMPDIR/idbench_logs_benchmark.csv; and the number parser alone
// (std::from_chars against fast_float) on the same kind of fields.
#include <benchmark/benchmark.h>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>

#if __has_include(<fast_float/fast_float.h>)  // libfast-float-dev, for the comparison only
#include <fast_float/fast_float.h>
#define IDBENCH_HAVE_FAST_FLOAT 1
#endif

#include "idbench/engine/puma560.h"
#include "idbench/logs/joint_log_csv_reader.h"
#include "idbench/logs/joint_log_csv_writer.h"
#include "idbench/logs/open_joint_log.h"
#include "idbench/logs/recorded_joint_log_source.h"

namespace idbench {
namespace {

constexpr Eigen::Index kSamples = 1'200'000;

// The log file, written on first use: smooth motions well inside puma560's
// limits, numbers in shortest round-trip form.
const std::string& LogPath() {
  static const std::string path = [] {
    const char* tmp = std::getenv("TMPDIR");
    const std::string p = std::string(tmp ? tmp : "/tmp") + "/idbench_logs_benchmark.csv";
    if (!std::filesystem::exists(p)) {
      JointLog log;
      log.t.resize(kSamples);
      log.q.resize(kSamples, 6);
      log.qd.resize(kSamples, 6);
      log.tau.resize(kSamples, 6);
      for (Eigen::Index s = 0; s < kSamples; ++s) {
        const double t = 1e-3 * static_cast<double>(s);
        log.t[s] = t;
        for (int j = 0; j < 6; ++j) {
          const double w = 0.3 + 0.1 * j;
          log.q(s, j) = 0.3 + 0.4 * std::sin(w * t + j);
          log.qd(s, j) = 0.4 * w * std::cos(w * t + j);
          log.tau(s, j) = 10.0 * std::sin(0.7 * t + 2.0 * j) + 0.01 * j;
        }
      }
      std::ofstream(p) << FormatJointLogCsv(log);
    }
    return p;
  }();
  return path;
}

void SetRates(benchmark::State& state) {
  const auto bytes = static_cast<int64_t>(std::filesystem::file_size(LogPath()));
  state.SetBytesProcessed(state.iterations() * bytes);
  state.SetItemsProcessed(state.iterations() * kSamples);
}

void BM_ReadCsvWhole(benchmark::State& state) {
  const RobotModel puma = MakePuma560();
  for (auto _ : state) {
    const RecordedJointLog log = ReadRecordedJointLog(LogPath(), puma, {}, TorqueColumns::kRequired);
    benchmark::DoNotOptimize(log.log.q.data());
  }
  SetRates(state);
}
BENCHMARK(BM_ReadCsvWhole)->Unit(benchmark::kMillisecond)->Iterations(3);

// Chunks of 65 536 samples, each dropped after reading (as a streaming consumer).
void BM_ReadCsvStreamed(benchmark::State& state) {
  const RobotModel puma = MakePuma560();
  for (auto _ : state) {
    const auto source = OpenJointLog(LogPath(), puma, {}, TorqueColumns::kRequired);
    JointLogChunk chunk;
    double sum = 0.0;
    while (source->Next(65536, &chunk)) sum += chunk.samples.q(0, 0);
    benchmark::DoNotOptimize(sum);
  }
  SetRates(state);
}
BENCHMARK(BM_ReadCsvStreamed)->Unit(benchmark::kMillisecond)->Iterations(3);

// Fields as the writer prints them (shortest round-trip decimals).
std::vector<std::string> Fields() {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  std::vector<std::string> fields;
  char buffer[32];
  for (int k = 0; k < 100000; ++k) {
    const auto end = std::to_chars(buffer, buffer + sizeof(buffer), u(rng)).ptr;
    fields.emplace_back(buffer, end);
  }
  return fields;
}

void BM_ParseDoubleFromChars(benchmark::State& state) {
  const std::vector<std::string> fields = Fields();
  for (auto _ : state) {
    double sum = 0.0, v = 0.0;
    for (const std::string& f : fields) {
      std::from_chars(f.data(), f.data() + f.size(), v);
      sum += v;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(fields.size()));
}
BENCHMARK(BM_ParseDoubleFromChars);

#ifdef IDBENCH_HAVE_FAST_FLOAT
void BM_ParseDoubleFastFloat(benchmark::State& state) {
  const std::vector<std::string> fields = Fields();
  for (auto _ : state) {
    double sum = 0.0, v = 0.0;
    for (const std::string& f : fields) {
      fast_float::from_chars(f.data(), f.data() + f.size(), v);
      sum += v;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(fields.size()));
}
BENCHMARK(BM_ParseDoubleFastFloat);
#endif

}  // namespace
}  // namespace idbench

BENCHMARK_MAIN();
