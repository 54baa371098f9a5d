// Upper bounds on what a user's counts, sizes and rates may ask of the
// machine, derived from it: one command holds at most a quarter of the
// physical memory at once (MemoryBudgetBytes), and runs at most four threads
// per hardware thread (more only wait). A request beyond them is refused
// before any work, naming the option, what it would need and the largest
// value this machine takes, instead of ending in std::bad_alloc after minutes.
#pragma once

#include <cstdint>
#include <string>

namespace idbench {

// A quarter of the machine's physical memory [bytes] (1 GiB if unknown).
std::uint64_t MemoryBudgetBytes();

// Four per hardware thread (at least 4).
int MaxThreads();

// Whether `count` `items` (e.g. "samples") of `bytes_each` fit in
// MemoryBudgetBytes(), and `count` in an int. Else false with *why = "OPTION:
// COUNT ITEMS would need SIZE (BYTES bytes each: WHAT), more than a quarter of
// this machine's memory (BUDGET); at most MAX ITEMS on this machine".
bool FitsInMemory(const std::string& option, double count, const std::string& items, double bytes_each,
                  const std::string& what, std::string* why);

// As FitsInMemory, throwing std::invalid_argument with *why.
void CheckFitsInMemory(const std::string& option, double count, const std::string& items, double bytes_each,
                       const std::string& what);

}  // namespace idbench
