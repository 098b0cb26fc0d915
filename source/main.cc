// bsmpm, the executable: reads the command line (bsmpm::CommandLine), runs
// the scene it describes (bsmpm::Scene) once, once per value of a --sweep
// (bsmpm::ParameterSweep) or on from a checkpoint (--resume), and reports an
// error with exit code 1 (bsmpm::ErrorReport). Everything else is in the
// library.
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <bsmpm/analysis/scene.h>
#include <bsmpm/analysis/strength_reduction.h>
#include <bsmpm/io/command_line.h>
#include <bsmpm/io/error_report.h>
#include <bsmpm/io/mpi_start.h>
#include <bsmpm/io/parameter_listing.h>
#include <bsmpm/io/parameter_sweep.h>
#include <bsmpm/io/run_checkpoint.h>

#include <iostream>
#include <string>

namespace
{
  /** One analysis of the parameters @p prm: a run in load steps, or the
   * factor of safety by strength reduction. */
  void
  run_analysis(dealii::ParameterHandler &prm)
  {
    if (bsmpm::StrengthReduction::enabled(prm))
      {
        bsmpm::StrengthReduction::run(prm, MPI_COMM_WORLD);
        return;
      }
    bsmpm::Scene scene(MPI_COMM_WORLD);
    scene.parse_parameters(prm);
    scene.run();
  }


  /** Runs the scene of the parameters @p prm on from the checkpoint
   * @p from. */
  void
  resume(dealii::ParameterHandler &prm, const std::string &from)
  {
    bsmpm::Scene scene(MPI_COMM_WORLD);
    scene.parse_parameters(prm);
    scene.resume_from(from);
    bsmpm::RunCheckpoint::explain_read_errors(from, [&]() { scene.run(); });
  }
} // namespace



int
main(int argc, char **argv)
{
  using namespace dealii;
  using namespace bsmpm;

  // --help and --print-parameters are answered before MPI starts and before
  // anything is built. Under mpirun only the first rank prints.
  CommandLine line;
  try
    {
      line = CommandLine(argc, argv);
    }
  catch (const std::exception &e)
    {
      std::cerr << "bsmpm: error: " << e.what() << std::endl;
      return 1;
    }
  if (line.help || line.print_parameters)
    {
      if (!launched_as_first_process())
        return 0;
      if (line.help)
        std::cout << CommandLine::usage;
      else
        {
          ParameterHandler prm;
          Scene::declare_parameters(prm);
          ParameterListing::print(prm, std::cout);
        }
      return 0;
    }

  start_mpi_quickly();
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const bool  root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  ErrorReport errors;

  try
    {
      ParameterHandler prm;
      Scene::declare_parameters(prm);

      if (!line.resume.empty())
        {
          // A resumed run takes the parameters of its checkpoint.
          const std::string from = line.read_checkpoint_parameters(prm);
          if (root)
            std::cout << "resuming from " << from << "\n";
          resume(prm, from);
          return 0;
        }

      line.read_parameters(prm);
      if (line.sweep.empty())
        {
          run_analysis(prm);
          return 0;
        }

      // A sweep: one run per value, one directory per run, in one process.
      const ParameterSweep sweep(line.sweep, prm);
      const unsigned int   n_runs = sweep.values().size();
      for (unsigned int k = 0; k < n_runs; ++k)
        {
          const std::string assignment = sweep.set_run(k, prm);
          if (root)
            std::cout << "\nsweep " << k + 1 << " of " << n_runs << ": "
                      << assignment << "\n";
          run_analysis(prm);
        }
      if (root)
        sweep.write_record();
    }
  catch (const ExceptionBase &e)
    {
      return errors.fail(message_of(e));
    }
  catch (const std::exception &e)
    {
      return errors.fail(e.what());
    }
  return 0;
}
