"""ddafit from Python: the DDA forward model of rapid landslides, its stable-friction search
and its back-analysis, in the field's words (docs/python.md).

    import ddafit
    scene = ddafit.load_scene("cases/vajont/degraded.yaml", set={"mesh.block_size": 34.3})
    run = ddafit.simulate(scene, threads=2)
    run.summary["points"]["1"]["max_lateral_displacement"]     # m, as in summary.json
    run.history["1"]["vx"]                                       # NumPy array, m/s

A scene or study that cannot be used raises ValueError with the one line the command line
prints. Ctrl-C stops a run and raises ddafit.Interrupted, whose .result keeps what it had.
"""
import os as _os
import warnings as _warnings

# Threads that wait must not spin on a shared machine: the command line bounds libgomp's
# spinning by re-executing itself with GOMP_SPINCOUNT set (batch/thread_budget.cpp); a
# Python process cannot, but libgomp reads the variable when it is loaded, which is when
# _core is imported below (unless something imported before ddafit loaded libgomp).
if "OMP_WAIT_POLICY" not in _os.environ and "GOMP_SPINCOUNT" not in _os.environ:
    _os.environ["GOMP_SPINCOUNT"] = "10000"

from . import _core  # noqa: E402
from ._core import Result, Scene, model_revision, version

__all__ = ["Scene", "Result", "Interrupted", "RunWarning", "load_scene", "mesh", "simulate", "stable", "invert",
           "model_revision", "version"]


class Interrupted(KeyboardInterrupt):
    """Ctrl-C stopped a run; .result is the run up to there (status "interrupted")."""

    def __init__(self, result):
        super().__init__("the run was interrupted; what it simulated is in .result")
        self.result = result


class RunWarning(UserWarning):
    """A warning of a run, as the command line prints it and summary.json lists it under
    "warnings": a setting known to degrade results, or an overlap over the 1 % of the smaller
    block the runs are checked to. simulate() raises each as a Python warning too."""


def _settings(set):
    return {str(k): v for k, v in dict(set or {}).items()}


def _scene_or_path(scene):
    return scene if isinstance(scene, Scene) else _os.fspath(scene)


def load_scene(path, set=None):
    """Reads a scene file; `set` changes settings by key as --set does, e.g.
    {"interfaces.clay.degradation_percent": 25, "time.integrator": "substep"}."""
    return _core.load_scene(_os.fspath(path), _settings(set))


def mesh(scene, block_size=None, set=None):
    """The scene's regions cut into blocks (at `block_size` m if given): a Scene whose
    outlines() are the blocks as N x 2 arrays. A Scene given is changed and returned."""
    settings = _settings(set)
    if block_size is not None:
        settings["mesh.block_size"] = block_size
    if isinstance(scene, Scene):
        for key, value in settings.items():
            scene[key] = value
        return scene
    return load_scene(scene, settings)


def simulate(scene, threads=0, set=None, mirror=False):
    """Runs the scene (a Scene or a path): a Result with .summary (the dict of
    summary.json), .history ({point: {"time", "x", "y", "ux", "uy", "vx", "vy"}} of NumPy
    arrays), .blocks (outlines at the last output) and .fixed. A run that fails keeps
    status "failed" and its message in the summary; an unusable scene raises ValueError.
    mirror=True runs the scene's mirror image (x -> -x) and returns it read back as the
    scene's own, as `ddafit simulate --mirror` does: its difference from the plain run is
    the answer's dependence on the order the solver meets the blocks in."""
    result = _core.simulate(_scene_or_path(scene), int(threads), _settings(set), bool(mirror))
    if result.summary["status"] == "interrupted":
        raise Interrupted(result)
    for warning in result.summary.get("warnings", []):
        _warnings.warn(warning, RunWarning, stacklevel=2)
    return result


def stable(scene, interface, low=5.0, high=45.0, tolerance=0.5, trial=10.0, rest_window=1.0, movement=0.0,
           set=None):
    """Bisects the friction angle of `interface` at which the scene comes to rest: the dict
    of stable.json (criterion, bracket, every trial)."""
    return _core.stable(_scene_or_path(scene), str(interface), float(low), float(high), float(tolerance),
                        float(trial), float(rest_window), float(movement), _settings(set))


def invert(study, out, resume=False, budget=0):
    """Fits a study (a YAML file) and writes its report into `out` (report.json, report.md,
    report.html, charts): the report as a dict, "friction" holding the bounding friction."""
    return _core.invert(_os.fspath(study), _os.fspath(out), bool(resume), int(budget))
