"""What the regression drivers of tests/liggghts share: running decks (runner), reading their
output (outputs), comparing two runs (compare) and the generated packs several folders use
(packs).  A driver puts tests/liggghts on sys.path and does `import common as C`."""

from .runner import COMMON, GEN, ROOT, Fail, Runner, driver_main, read_text  # noqa: F401
from .outputs import (parse_atoms_dump, parse_dump_rows, parse_local_dump, parse_stats,  # noqa: F401
                      parse_thermo)
from .checks import Checks, case_dispatch  # noqa: F401
from .compare import (THERMO_RTOL, compare_pairsets, cross_pairs, cutoff_info,  # noqa: F401
                      report_thermo, thermo_diff)
from .packs import PAIR_CASES, PAIR_VARS, SETTLE_GEN, SETTLE_WIDE_GEN  # noqa: F401
