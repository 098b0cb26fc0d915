#ifndef bsmpm_move_diagnosis_h
#define bsmpm_move_diagnosis_h

#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/points/material_points.h>

#include <string>

namespace bsmpm
{
  /**
   * Why material points left the background grid in a load step, told
   * from what the step can see (MaterialPoints::MoveReport): displacements
   * that are not finite, a point from a poorly supported cell, loads far
   * too large for the material, a load step too large for small-strain
   * MPM, or a grid too small for the body. The message says what to change.
   */
  class MoveDiagnosis
  {
  public:
    /**
     * The error message for load step @p step whose move @p report says
     * that points left @p grid. @p quality_threshold and @p stabilised:
     * the ghost penalty's quality threshold and whether it is enabled.
     */
    static std::string
    message(const MaterialPoints::MoveReport &report,
            const unsigned int                step,
            const BackgroundGrid             &grid,
            const double                      quality_threshold,
            const bool                        stabilised);

  private:
    /** The likely cause and its remedy. */
    static std::string
    cause(const MaterialPoints::MoveReport &report,
          const BackgroundGrid             &grid,
          const double                      quality_threshold,
          const bool                        stabilised);
  };
} // namespace bsmpm

#endif
