"""The seven parameter sweeps of keff_parameters.py (docs/results/keff-parameters.md), one module
each, in the page's order: temperature, ratio, young, emissivity, height, psd, consolidation.
Each has run() (the measurements, beds made or read from their caches), section() (its part of
the page) and panel() (its part of the figure); shared.py holds the beds and the keff run they
have in common. keff_parameters.py runs them and writes the page."""
