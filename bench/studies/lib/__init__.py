"""What the study scripts of bench/studies/ share, so that no study imports another:

- apps.py: where the build is, one program run with --json, the options a program resolves
  (--print-config), and the wrappers of deposit, bedstat, keff and sinter (with the beds and
  stored runs more than one study uses);
- references.py: the reference models and published numbers the studies compare with, each
  with its source;
- pce.py: the second-order polynomial chaos on a Smolyak sparse grid (keff-validation.md's
  input uncertainty);
- report.py: writing a results page, its table cells, and the machine a study ran on.

Run a study as `python3 bench/studies/NAME.py`: its folder is then first on the module path and
`from lib import apps` finds this package. The tests (lib/tests/, pytest) run from ctest.
"""
