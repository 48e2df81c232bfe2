#include "cvode_impacts.hpp"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "oscillator_model.hpp"

namespace impactkit::reference {
namespace {

template <class Handle>
Handle CheckCreated(Handle handle, const char* call) {
  if (handle == nullptr) throw std::runtime_error(std::string("CVODE: ") + call + " failed");
  return handle;
}

struct SundialsDeleter {
  void operator()(SUNContext context) const { SUNContext_Free(&context); }
  void operator()(N_Vector vector) const { N_VDestroy(vector); }
  void operator()(SUNMatrix matrix) const { SUNMatDestroy(matrix); }
  void operator()(SUNLinearSolver solver) const { SUNLinSolFree(solver); }
};

struct CvodeMemoryDeleter {
  void operator()(void* memory) const { CVodeFree(&memory); }
};

template <class Handle>
using Owned = std::unique_ptr<std::remove_pointer_t<Handle>, SundialsDeleter>;

// What the C callbacks see through user_data. Those called while stepping
// (right-hand side, Jacobian, root) must not throw: they do not allocate.
struct CallbackData {
  explicit CallbackData(const LinearOscillator& o) : oscillator(o), jacobian(o.Jacobian()) {}

  const LinearOscillator& oscillator;
  const Eigen::MatrixXd jacobian;
  const ImpactSequence* impacts = nullptr;  // set when impacts are roots
  long rhs_evaluations = 0;
  std::string last_error;
};

// CVODE reports here instead of printing to stderr. Errors reach the caller
// in the exception; warnings are dropped (the only expected one: a restart
// exactly on the stop at rest, where the root function is identically 0).
void KeepError(int error_code, const char* /*module*/, const char* function, char* message,
               void* user_data) {
  if (error_code >= 0) return;
  try {
    static_cast<CallbackData*>(user_data)->last_error = std::string(function) + ": " + message;
  } catch (...) {  // out of memory: the flag alone will have to do
  }
}

int Rhs(sunrealtype t, N_Vector y, N_Vector dydt, void* user_data) {
  auto* data = static_cast<CallbackData*>(user_data);
  ++data->rhs_evaluations;
  data->oscillator.Derivative(t, N_VGetArrayPointer(y), N_VGetArrayPointer(dydt));
  return 0;
}

int Jacobian(sunrealtype /*t*/, N_Vector /*y*/, N_Vector /*dydt*/, SUNMatrix jacobian,
             void* user_data, N_Vector /*tmp1*/, N_Vector /*tmp2*/, N_Vector /*tmp3*/) {
  const Eigen::MatrixXd& exact = static_cast<CallbackData*>(user_data)->jacobian;
  // SUNDenseMatrix stores its entries column-major and contiguous, like Eigen.
  Eigen::Map<Eigen::MatrixXd>(SUNDenseMatrix_Data(jacobian), exact.rows(), exact.cols()) = exact;
  return 0;
}

int ImpactRoot(sunrealtype /*t*/, N_Vector y, sunrealtype* g, void* user_data) {
  const ImpactSequence& impacts = *static_cast<CallbackData*>(user_data)->impacts;
  for (int k = 0; k < impacts.StopCount(); ++k) g[k] = impacts.Gap(k, N_VGetArrayPointer(y));
  return 0;
}

// One CVODE integrator of a LinearOscillator and everything it owns. Members
// are destroyed in reverse order: the integrator before its solver, matrix and
// vector, the SUNContext last. Not movable: CVODE keeps a pointer to data_.
class Cvode {
 public:
  Cvode(const LinearOscillator& oscillator, double t0, const Eigen::VectorXd& y0, double rtol,
        double atol, double max_step)
      : data_(oscillator), t_(t0) {
    SUNContext context = nullptr;
    Check(SUNContext_Create(nullptr, &context), "SUNContext_Create");
    context_.reset(context);
    const auto size = static_cast<sunindextype>(y0.size());
    y_.reset(CheckCreated(N_VNew_Serial(size, context), "N_VNew_Serial"));
    State() = y0;
    matrix_.reset(CheckCreated(SUNDenseMatrix(size, size, context), "SUNDenseMatrix"));
    solver_.reset(
        CheckCreated(SUNLinSol_Dense(y_.get(), matrix_.get(), context), "SUNLinSol_Dense"));
    memory_.reset(CheckCreated(CVodeCreate(CV_ADAMS, context), "CVodeCreate"));
    void* cvode = memory_.get();
    Check(CVodeSetErrHandlerFn(cvode, KeepError, &data_), "CVodeSetErrHandlerFn");
    Check(CVodeInit(cvode, Rhs, t0, y_.get()), "CVodeInit");
    Check(CVodeSetUserData(cvode, &data_), "CVodeSetUserData");
    Check(CVodeSStolerances(cvode, rtol, atol), "CVodeSStolerances");
    Check(CVodeSetLinearSolver(cvode, solver_.get(), matrix_.get()), "CVodeSetLinearSolver");
    Check(CVodeSetJacFn(cvode, Jacobian), "CVodeSetJacFn");
    // Long runs between roots are normal here; a negative limit disables the
    // default cap of 500 steps per CVode call.
    Check(CVodeSetMaxNumSteps(cvode, -1), "CVodeSetMaxNumSteps");
    if (max_step > 0.0) Check(CVodeSetMaxStep(cvode, max_step), "CVodeSetMaxStep");
  }
  Cvode(const Cvode&) = delete;
  Cvode& operator=(const Cvode&) = delete;

  // Stop at upward crossings of each stop's g = s (x_c - xs), one root
  // function per stop. CVODE never reports a root at
  // the initial point of a (re)start. A restart after an impact is at g >= 0
  // (CVODE returns the far side of the root) and g then falls (v_c < 0, or
  // v_c = 0 with a_c <= 0: else the run has stopped), which the direction
  // filter ignores: the same impact cannot be reported twice.
  void StopAtImpacts(const ImpactSequence& impacts) {
    data_.impacts = &impacts;
    Check(CVodeRootInit(memory_.get(), impacts.StopCount(), ImpactRoot), "CVodeRootInit");
    std::vector<int> upwards(impacts.StopCount(), 1);
    Check(CVodeSetRootDirection(memory_.get(), upwards.data()), "CVodeSetRootDirection");
  }

  // The stops whose roots were found at the returned time (two when
  // their crossings fall in one step's root bracket).
  std::vector<int> RootStops() const {
    std::vector<int> found(data_.impacts->StopCount()), stops;
    Check(CVodeGetRootInfo(memory_.get(), found.data()), "CVodeGetRootInfo");
    for (int k = 0; k < static_cast<int>(found.size()); ++k) {
      if (found[k] != 0) stops.push_back(k);
    }
    return stops;
  }

  // Integrates towards t_out; returns true if it stopped at a root before.
  // t_out is also the stop time, so CVODE never evaluates beyond it.
  bool AdvanceTo(double t_out) {
    Check(CVodeSetStopTime(memory_.get(), t_out), "CVodeSetStopTime");
    const int flag = CVode(memory_.get(), t_out, y_.get(), &t_, CV_NORMAL);
    Check(flag, "CVode");
    return flag == CV_ROOT_RETURN;
  }

  // Restarts from the current (t, State()), which the caller has changed.
  void Restart() { Check(CVodeReInit(memory_.get(), t_, y_.get()), "CVodeReInit"); }

  double t() const { return t_; }
  Eigen::Map<Eigen::VectorXd> State() {
    return {N_VGetArrayPointer(y_.get()), N_VGetLength_Serial(y_.get())};
  }
  long rhs_evaluations() const { return data_.rhs_evaluations; }

 private:
  void Check(int flag, const char* call) const {
    if (flag >= 0) return;
    std::string what = std::string("CVODE: ") + call + " failed with flag " + std::to_string(flag);
    if (!data_.last_error.empty()) what += " (" + data_.last_error + ")";
    throw std::runtime_error(what);
  }

  CallbackData data_;
  sunrealtype t_;
  Owned<SUNContext> context_;
  Owned<N_Vector> y_;
  Owned<SUNMatrix> matrix_;
  Owned<SUNLinearSolver> solver_;
  std::unique_ptr<void, CvodeMemoryDeleter> memory_;
};

}  // namespace

ReferenceRun CvodeImpacts(const System& s, Eigen::VectorXd x0, Eigen::VectorXd v0, double t0,
                          double t_end, const CvodeOptions& o) {
  const LinearOscillator oscillator(s);
  double farthest = 0.0;
  for (const StopParameters& stop : s.stops) farthest = std::max(farthest, std::abs(stop.position));
  ImpactSequence sequence(s, oscillator, o.max_impacts, o.min_interimpact,
                          o.atol + o.rtol * farthest);
  Eigen::VectorXd y0 = oscillator.StackState(x0, v0);
  if (!sequence.Begin(t0, y0) || t_end <= t0) return sequence.Finish(t0, y0, 0);

  Cvode cvode(oscillator, t0, y0, o.rtol, o.atol, o.max_step);
  cvode.StopAtImpacts(sequence);
  // A root exactly at t_end is left for a run that goes further, as odeint does.
  bool going = true;
  while (going && cvode.AdvanceTo(t_end) && cvode.t() < t_end) {
    for (int stop : cvode.RootStops())
      going = going && sequence.Impact(cvode.t(), cvode.State(), stop);
    if (going) cvode.Restart();
  }
  return sequence.Finish(cvode.t(), cvode.State(), cvode.rhs_evaluations());
}

void CvodeLinearFlow(const Eigen::MatrixXd& M, const Eigen::MatrixXd& C, const Eigen::MatrixXd& K,
                     const Eigen::VectorXd& A, const Eigen::VectorXd& f0, double omega, double t0,
                     Eigen::VectorXd& x, Eigen::VectorXd& v, double t1, double rtol, double atol) {
  if (t1 == t0) return;  // CVODE rejects a zero-length interval
  const LinearOscillator oscillator(M, C, K, A, f0, omega);
  Cvode cvode(oscillator, t0, oscillator.StackState(x, v), rtol, atol, 0.0);
  cvode.AdvanceTo(t1);
  const Eigen::Index n = oscillator.Dof();
  x = cvode.State().head(n);
  v = cvode.State().tail(n);
}

}  // namespace impactkit::reference
