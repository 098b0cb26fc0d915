#ifndef bsmpm_load_level_h
#define bsmpm_load_level_h

namespace bsmpm
{
  /**
   * The multipliers of a scene's loads at one point of its load path
   * (LoadStages).
   */
  struct LoadLevel
  {
    /** Multiplies Loading/Gravity (the body force). */
    double gravity = 0;
    /** Multiplies the tractions and pressures of the curves and their
     * prescribed displacements; the t of the rigid bodies' Displacement and
     * Force expressions. */
    double loads = 0;
    /** Multiplies the forces that the material removed by an excavation
     * exerted on the rest (Excavation): 1 at the stage's start, 0 at its
     * end. */
    double release = 0;
  };



  /**
   * One load increment: the loads multiplier (LoadLevel::loads, the t of
   * expressions) from @p from to @p to. Prescribed displacements are
   * imposed by their change over it.
   */
  struct LoadIncrement
  {
    double from = 0;
    double to   = 0;

    /** The growth of the multiplier: what scales a prescribed
     * displacement that is not an expression of t. */
    double
    share() const
    {
      return to - from;
    }
  };
} // namespace bsmpm

#endif
