// The memory budget of a run (see memory_budget.h).
#include "engine/core/memory_budget.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>

namespace ptlab {
namespace {

std::atomic<uint64_t> g_budget{0};

}  // namespace

uint64_t DefaultMemoryBudgetBytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page <= 0) return uint64_t(8) << 30;
  const uint64_t ram = uint64_t(pages) * uint64_t(page);
  const uint64_t budget = ram / 4 * 3;
  return budget < (uint64_t(256) << 20) ? uint64_t(256) << 20 : budget;
}

uint64_t MemoryBudgetBytes() {
  const uint64_t set = g_budget.load(std::memory_order_relaxed);
  return set != 0 ? set : DefaultMemoryBudgetBytes();
}

void SetMemoryBudgetBytes(uint64_t bytes) { g_budget.store(bytes, std::memory_order_relaxed); }

uint64_t ExpansionBudgetBytes(uint64_t input_bytes) {
  if (g_budget.load(std::memory_order_relaxed) != 0) return MemoryBudgetBytes();
  const uint64_t scaled = input_bytes > kMinExpansionBudgetBytes / kMaxExpansionPerInputByte
                              ? input_bytes * kMaxExpansionPerInputByte
                              : kMinExpansionBudgetBytes;
  return std::min(MemoryBudgetBytes(), std::max(scaled, kMinExpansionBudgetBytes));
}

std::string FormatBytes(double bytes) {
  char buf[64];
  if (bytes >= double(uint64_t(1) << 30))
    std::snprintf(buf, sizeof buf, "%.3g GiB", bytes / double(uint64_t(1) << 30));
  else
    std::snprintf(buf, sizeof buf, "%.3g MiB", bytes / double(uint64_t(1) << 20));
  return buf;
}

std::string OverMemoryBudget(double bytes, const std::string& what) {
  const uint64_t budget = MemoryBudgetBytes();
  if (!(bytes > double(budget))) return std::string();
  const bool set = g_budget.load(std::memory_order_relaxed) != 0;
  return what + " would take about " + FormatBytes(bytes) + "; expected at most " +
         FormatBytes(double(budget)) +
         (set ? " (--max-memory)" : " (--max-memory; the default is 3/4 of this machine's RAM)");
}

std::string OverExpansionBudget(double bytes, uint64_t input_bytes, const std::string& what) {
  const uint64_t budget = ExpansionBudgetBytes(input_bytes);
  if (!(bytes > double(budget))) return std::string();
  if (g_budget.load(std::memory_order_relaxed) != 0) return OverMemoryBudget(bytes, what);
  return what + " would take about " + FormatBytes(bytes) + "; expected at most " +
         FormatBytes(double(budget)) + " for a file of " + std::to_string(input_bytes) +
         " bytes (by default the smaller of 3/4 of this machine's RAM and max(2 GiB, " +
         std::to_string(kMaxExpansionPerInputByte) + " x the file's size); --max-memory sets it)";
}

}  // namespace ptlab
