"""PASS/FAIL checks of the drivers that run named cases (trimesh_walls, trimesh_spheres,
move_trimesh): every check prints its line, a case fails at its end if any check failed."""

from .runner import Fail


class Checks:
    def __init__(self):
        self.failed = []

    def __call__(self, cond, what):
        print(("PASS " if cond else "FAIL ") + what, flush=True)
        if not cond:
            self.failed.append(what)

    def raise_if_failed(self):
        if self.failed:
            raise Fail("%d check(s) failed: %s" % (len(self.failed), "; ".join(self.failed)))


def case_dispatch(cases, checks, before=None):
    """dispatch(R, parts) for driver_main: runs cases[parts[0]](R) (after before(R), if given),
    then fails if a check failed; False for an unknown case."""
    def dispatch(R, parts):
        if parts[0] not in cases:
            return False
        if before:
            before(R)
        cases[parts[0]](R)
        checks.raise_if_failed()
        return True
    return dispatch
