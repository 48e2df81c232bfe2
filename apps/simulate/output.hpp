#pragma once
/// \file simulate/output.hpp
/// The files `impactkit simulate` writes:
///
///     --series   t,x1..xN,v1..vN,stuck    one row per sample of the window
///     --impacts  t,phase,velocity,x1..xN,v1..vN  one row per impact (velocity: speed of
///                                         the contact mass just before it;
///                                         x, v: the state just before it)
///     --plot     x1..xN against t, the contact mass solid, the stop dotted
///     --json     the summary (simulate/summary.hpp)
///
/// All are created as temporaries before the run, so an unwritable path
/// fails first, and appear only once all are complete.

#include <optional>
#include <string>

#include "common/provenance.hpp"
#include "impactkit/io/output_set.hpp"
#include "simulate/run.hpp"

namespace impactkit::cli {

class SimulateOutputs {
 public:
  /// Throws OutputError if a file cannot be created.
  SimulateOutputs(const SimulateRequest& request, const System& system, Provenance provenance);

  /// Whether the window's time series must be recorded (--series or --plot).
  bool NeedsSeries() const { return series_ != nullptr || plot_ != nullptr; }

  /// Writes every requested file, then moves them all into place.
  void Write(const SimulateResult& result);

 private:
  void WriteSeries(const SimulateResult& result);
  void WriteImpacts(const SimulateResult& result);

  Provenance provenance_;
  OutputSet set_;
  CsvWriter* series_ = nullptr;  ///< each in set_; nullptr when not asked for
  CsvWriter* impacts_ = nullptr;
  AtomicOutputFile* plot_ = nullptr;
  AtomicOutputFile* json_ = nullptr;
};

}  // namespace impactkit::cli
