// The memory budget of a run: how many bytes a scene and a render may take, set once by the
// tool (ptlab --max-memory) and read by the loaders and the render's up-front estimate, so an
// input of a few kilobytes that would expand into gigabytes is an error that says how much it
// would need, before the memory is taken.
#pragma once

#include <cstdint>
#include <string>

namespace ptlab {

/// Bytes of scene memory one triangle costs, about: its traversal and shading rows, its share
/// of the vertex table, the BVH and the 8-wide BVH, and the builders' temporaries (the README's
/// 10^7-triangle height field peaks at 1.5 GB).
inline constexpr uint64_t kSceneBytesPerTriangle = 160;

/// The default budget: three quarters of the machine's physical memory (sysconf), at least
/// 256 MiB; 8 GiB when the system does not say.
uint64_t DefaultMemoryBudgetBytes();

/// The budget in force: what SetMemoryBudgetBytes set, else DefaultMemoryBudgetBytes().
uint64_t MemoryBudgetBytes();

/// Sets the budget (0: back to the default).
void SetMemoryBudgetBytes(uint64_t bytes);

/// A small file may not expand (by instancing) into more than this many times its own bytes,
/// nor into more than kMinExpansionBudgetBytes, unless --max-memory says otherwise.
inline constexpr uint64_t kMaxExpansionPerInputByte = 4096;
inline constexpr uint64_t kMinExpansionBudgetBytes = uint64_t(2) << 30;

/// What a scene file of `input_bytes` may expand into: with --max-memory given, that budget;
/// by default the smaller of MemoryBudgetBytes() and max(2 GiB, 4096 x input_bytes), so a file
/// of a few kilobytes cannot claim gigabytes through its instances.
uint64_t ExpansionBudgetBytes(uint64_t input_bytes);

/// "1.5 GiB", "640 MiB": a byte count for messages.
std::string FormatBytes(double bytes);

/// Empty when `bytes` (what `what` would take) fits the budget; else a message with both
/// figures and how to raise the budget, e.g. "the scene would take about 24.0 GiB (2^27
/// triangles); expected at most 11.6 GiB (--max-memory, default 3/4 of this machine's RAM)".
std::string OverMemoryBudget(double bytes, const std::string& what);

/// As OverMemoryBudget, against ExpansionBudgetBytes(input_bytes).
std::string OverExpansionBudget(double bytes, uint64_t input_bytes, const std::string& what);

}  // namespace ptlab
