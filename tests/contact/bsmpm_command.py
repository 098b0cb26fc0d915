"""The command line of one bsmpm run for the contact check scripts: under
mpirun when np > 1, the parameter file, the output directory and the
parameter assignments, in this order."""
import pathlib


def bsmpm_command(bsmpm, prm, directory, settings, np=1):
    """Arguments for subprocess: bsmpm on @p prm writing into @p directory,
    with each of @p settings ("Section/Name=value") as a --set."""
    command = ([] if np == 1 else
               ["mpirun", "--allow-run-as-root", "--oversubscribe",
                "-np", str(np)])
    command += [str(pathlib.Path(bsmpm).resolve()),
                str(pathlib.Path(prm).resolve()),
                "--set", f"Output/Directory={directory}"]
    for s in settings:
        command += ["--set", s]
    return command
