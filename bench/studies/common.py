"""The names spread_peer.py, spread_layers.py, spread_accuracy.py and build_layers.py import from
the studies' old shared module. It remains only for those four scripts, which are being changed
elsewhere, until they import lib/ (bench/studies/lib/apps.py and report.py) like every other
study; then this file goes."""
from lib.apps import ROOT, app, bedstat, run_json
from lib.report import RESULTS
from lib.report import write_page as write_text

__all__ = ["ROOT", "RESULTS", "app", "bedstat", "run_json", "write_text"]
