#ifndef bsmpm_load_step_record_h
#define bsmpm_load_step_record_h

#include <string>
#include <vector>

namespace bsmpm
{
  /** What the solver did in one load step: the figures of the step table
   * and of summary.json (RunSummary::Step adds the step's number and the
   * scene's quantities). */
  struct LoadStepRecord
  {
    double       load_factor = 0;
    std::string  solver;
    unsigned int iterations        = 0;
    unsigned int refinement_steps  = 0;
    double       relative_residual = 0;
    unsigned int n_active_cells    = 0;
    /** Nonlinear materials: load increments the step took (more than
     * one after cuts), points that yielded, and per Newton iteration of
     * all its increments the relative residual and correction. */
    unsigned int        increments = 1;
    unsigned long long  n_yielded  = 0;
    std::vector<double> newton_residuals;
    std::vector<double> newton_corrections;
    /** Increments of the step whose last cut did not converge but whose
     * best iterate was accepted (Nonlinear solver/Stall tolerance), and
     * the largest of their residuals relative to the largest internal
     * force; 0 if none. */
    unsigned int stalled_increments = 0;
    double       stalled_residual   = 0;
  };
} // namespace bsmpm

#endif
