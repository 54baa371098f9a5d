#include "idbench/engine/resource_limits.h"

#include <unistd.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <thread>

namespace idbench {
namespace {

// Bytes as a message shows them: "1.5 GB", "12 MB".
std::string Size(double bytes) {
  char text[32];
  if (bytes >= 1e9) std::snprintf(text, sizeof(text), "%.3g GB", bytes / 1e9);
  else std::snprintf(text, sizeof(text), "%.3g MB", bytes / 1e6);
  return text;
}

}  // namespace

std::uint64_t MemoryBudgetBytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page_size = sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page_size <= 0) return std::uint64_t{1} << 30;
  return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page_size) / 4;
}

int MaxThreads() { return 4 * std::max(1, static_cast<int>(std::thread::hardware_concurrency())); }

bool FitsInMemory(const std::string& option, double count, const std::string& items, double bytes_each,
                  const std::string& what, std::string* why) {
  const double budget = static_cast<double>(MemoryBudgetBytes());
  const double max_count = std::min(std::floor(budget / bytes_each), static_cast<double>(INT_MAX));
  if (count <= max_count) return true;
  char value[32];
  std::snprintf(value, sizeof(value), "%.15g", count);
  if (why) {
    *why = option + ": " + value + " " + items + " would need " + Size(count * bytes_each) + " (" +
           std::to_string(static_cast<long long>(bytes_each)) + " bytes each: " + what +
           "), more than a quarter of this machine's memory (" + Size(budget) + "); at most " +
           std::to_string(static_cast<long long>(max_count)) + " " + items + " on this machine";
  }
  return false;
}

void CheckFitsInMemory(const std::string& option, double count, const std::string& items, double bytes_each,
                       const std::string& what) {
  std::string why;
  if (!FitsInMemory(option, count, items, bytes_each, what, &why)) throw std::invalid_argument(why);
}

}  // namespace idbench
