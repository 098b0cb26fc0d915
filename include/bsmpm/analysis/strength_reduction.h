#ifndef bsmpm_strength_reduction_h
#define bsmpm_strength_reduction_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <bsmpm/io/run_summary.h>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The factor of safety of a scene by strength reduction (section
   * "Strength reduction", doc/limit-loads.md): the scene's loads (gravity,
   * tractions) are applied in its load steps as usual, with the strength
   * of the material divided by a trial factor F (von Mises: the yield
   * stress; Drucker-Prager: c and tan(phi)). A trial collapses when the
   * CollapseDetector declares a limit load below load factor 1. The factor
   * of safety is the largest F that does not collapse, found by bisection
   * in 'Bracket' to 'Tolerance'; every trial is a run of its own from the
   * unloaded body, in Output/Directory/trial-<k>.
   *
   * The trials start from the unloaded body (not from the state of the
   * last trial), so that each factor gives the same answer whatever the
   * order of the bisection: with non-associated flow the state reached
   * depends on the path.
   */
  class StrengthReduction
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    /** Whether the parameters ask for a factor of safety. */
    static bool
    enabled(ParameterHandler &prm);

    /** Runs the trials and writes Output/Directory/summary.json with
     * factor_of_safety and its bracket; throws where a verification bound
     * fails. */
    static RunSummary
    run(ParameterHandler &prm, const MPI_Comm communicator);
  };
} // namespace bsmpm

#endif
