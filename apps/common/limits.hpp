#pragma once
/// \file common/limits.hpp
/// Upper bounds on every count a command takes, and the check of output
/// paths. Without them a typo (an extra digit, a pasted number) is taken at
/// its word: a run of 1e11 periods that never ends, a sweep that exhausts
/// memory, a sum of two counts that overflows. Each bound is far above
/// what real work asks for (the paper's longest run is 5000 periods, its
/// sweep 2401 values), so that only a mistake meets it.

#include <CLI/CLI.hpp>
#include <climits>
#include <string>

namespace impactkit::cli {

/// Forcing periods of one run or window (--transient, --periods, --record):
/// 1e7 periods take hours of simulation even for a single mass, and the
/// impacts of a recorded window are held in memory.
inline constexpr long long kMaxPeriods = 10'000'000;
/// Values along one axis (sweep and resonance --steps, --chunk, --warmup):
/// a million values resolve any diagram a screen or a page can show.
inline constexpr long long kMaxSteps = 1'000'000;
/// Samples per forcing period (simulate --samples-per-period): far finer
/// than any plot, and the series is bounded by its row count besides.
inline constexpr long long kMaxSamplesPerPeriod = 100'000;
/// Map iterations (lyapunov --impacts, --transient-impacts): the
/// exponents converge like 1/sqrt(impacts); 1e7 is far past any use.
inline constexpr long long kMaxImpacts = 10'000'000;
/// p and q of an orbit (--p, --q) and the longest period searched
/// (--max-q): an orbit of more than a thousand impacts or periods is
/// beyond what a fixed-point solve can resolve (its multipliers underflow
/// long before); the paper's longest is P(2,2).
inline constexpr long long kMaxOrbitPeriod = 1'000;
/// Points per direction of a continued branch (--max-points).
inline constexpr long long kMaxBranchPoints = 1'000'000;
/// Worker threads (--threads): more than any machine's cores by far.
inline constexpr long long kMaxThreads = 1'024;

/// The commands add counts (transient + recorded periods) in int: with
/// every count within its bound, no such sum can overflow.
static_assert(2 * kMaxPeriods + 1 <= INT_MAX, "a sum of two period counts must fit an int");
static_assert(2 * kMaxOrbitPeriod + 1 <= INT_MAX, "2 max_q + 1 must fit an int");

/// A CLI11 check for an integer option: refuses a value above `limit` (or
/// beyond any integer type) with "--FLAG: at most LIMIT UNIT, got VALUE".
/// Lower bounds stay with each command, whose messages say what the value
/// means; text that is not an integer is left to CLI11's conversion error.
CLI::Validator AtMost(long long limit, const std::string& unit);

/// A CLI11 check for an output path: an empty one, which would otherwise
/// read as "not asked for" and silently write nothing, is refused as naming
/// no `noun` ("file", "folder").
CLI::Validator OutputPath(const std::string& noun = "file");

}  // namespace impactkit::cli
