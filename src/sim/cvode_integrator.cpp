#include "gaitopt/sim/cvode_integrator.hpp"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace gaitopt {

struct CvodeIntegrator::Impl {
  int n, n_roots;
  Rhs rhs;
  Roots roots;
  SUNContext ctx = nullptr;
  N_Vector y = nullptr;
  SUNNonlinearSolver nls = nullptr;
  void* mem = nullptr;
  Eigen::VectorXd y_buf, f_buf, g_buf;
  std::string last_error;  // CVODE's message of the last failure (instead of its stderr line)

  static int f(realtype t, N_Vector y, N_Vector ydot, void* data) {
    Impl& s = *static_cast<Impl*>(data);
    s.y_buf = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(y), s.n);
    s.rhs(t, s.y_buf, s.f_buf);
    Eigen::Map<Eigen::VectorXd>(N_VGetArrayPointer(ydot), s.n) = s.f_buf;
    return s.f_buf.allFinite() ? 0 : 1;  // recoverable: CVODE retries with a smaller step
  }
  static int g(realtype t, N_Vector y, realtype* gout, void* data) {
    Impl& s = *static_cast<Impl*>(data);
    s.y_buf = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(y), s.n);
    s.roots(t, s.y_buf, s.g_buf);
    Eigen::Map<Eigen::VectorXd>(gout, s.n_roots) = s.g_buf;
    return 0;
  }
  static void error(int, const char*, const char*, char* message, void* data) {
    static_cast<Impl*>(data)->last_error = message;
  }
};

namespace {
void check(int flag, const char* what) {
  if (flag < 0) throw std::runtime_error(std::string("CVODE: ") + what + " failed, flag " +
                                         std::to_string(flag));
}
}  // namespace

CvodeIntegrator::CvodeIntegrator(int n, const Rhs& rhs, int n_roots, const Roots& roots,
                                 const CvodeTolerances& tol)
    : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.n = n;
  s.n_roots = n_roots;
  s.rhs = rhs;
  s.roots = roots;
  s.f_buf.resize(n);
  s.g_buf.resize(n_roots);
  check(SUNContext_Create(nullptr, &s.ctx), "SUNContext_Create");
  s.y = N_VNew_Serial(n, s.ctx);
  N_VConst(0.0, s.y);
  s.mem = CVodeCreate(CV_ADAMS, s.ctx);
  if (!s.mem) throw std::runtime_error("CVODE: CVodeCreate failed");
  check(CVodeInit(s.mem, Impl::f, 0.0, s.y), "CVodeInit");
  check(CVodeSetUserData(s.mem, &s), "CVodeSetUserData");
  check(CVodeSetErrHandlerFn(s.mem, Impl::error, &s), "CVodeSetErrHandlerFn");
  if (tol.absolute_per_component.size() == n) {
    N_Vector atol = N_VNew_Serial(n, s.ctx);
    Eigen::Map<Eigen::VectorXd>(N_VGetArrayPointer(atol), n) = tol.absolute_per_component;
    const int flag = CVodeSVtolerances(s.mem, tol.relative, atol);  // copies atol
    N_VDestroy(atol);
    check(flag, "CVodeSVtolerances");
  } else {
    check(CVodeSStolerances(s.mem, tol.relative, tol.absolute), "CVodeSStolerances");
  }
  s.nls = SUNNonlinSol_FixedPoint(s.y, 0, s.ctx);
  check(CVodeSetNonlinearSolver(s.mem, s.nls), "CVodeSetNonlinearSolver");
  check(CVodeSetMaxNumSteps(s.mem, 100000), "CVodeSetMaxNumSteps");
  if (n_roots > 0) {
    check(CVodeRootInit(s.mem, n_roots, Impl::g), "CVodeRootInit");
    std::vector<int> falling(n_roots, -1);  // events are crossings from positive to negative
    check(CVodeSetRootDirection(s.mem, falling.data()), "CVodeSetRootDirection");
  }
}

CvodeIntegrator::~CvodeIntegrator() {
  CVodeFree(&impl_->mem);
  SUNNonlinSolFree(impl_->nls);
  N_VDestroy(impl_->y);
  SUNContext_Free(&impl_->ctx);
}

void CvodeIntegrator::reset(double t0, const Eigen::VectorXd& y0) {
  Eigen::Map<Eigen::VectorXd>(N_VGetArrayPointer(impl_->y), impl_->n) = y0;
  check(CVodeReInit(impl_->mem, t0, impl_->y), "CVodeReInit");
}

CvodeIntegrator::Result CvodeIntegrator::advance(double t_end) {
  Impl& s = *impl_;
  realtype t = 0.0;
  const int flag = CVode(s.mem, t_end, s.y, &t, CV_NORMAL);
  if (flag < 0)
    throw IntegrationError(t, "CVODE stopped at t = " + std::to_string(t) + " s: " +
                                  (s.last_error.empty() ? "flag " + std::to_string(flag)
                                                        : s.last_error));
  Result r{t, Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(s.y), s.n), -1};
  if (flag == CV_ROOT_RETURN) {
    std::vector<int> found(s.n_roots);
    check(CVodeGetRootInfo(s.mem, found.data()), "CVodeGetRootInfo");
    for (int i = 0; i < s.n_roots; ++i)
      if (found[i] != 0) {
        r.root = i;
        break;
      }
  }
  return r;
}

}  // namespace gaitopt
