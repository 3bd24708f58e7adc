"""lib/apps.py's reading of --print-config, on text written as the programs write it
(apps/common/options.cpp print_config_text), and its dosed build spread as this build's deposit
resolves it (POWDERBED_BUILD). Run from bench/studies: python3 -m pytest lib/tests"""
import shlex

import pytest

from lib import apps

PRINTED = """\
# deposit 0.1.0: the resolved options (--config reads this back from any folder; defaults and a material file's values commented out)
# allow-lost = 0  (default)
domain = 2.6e-3,0.5e-3,1.2e-3
# material.density = 8900  (from --material)
# recoater.tool =   (default)
psd = "mono:d=30e-6 #x"
# fines.scaling = "a  (b\\"\\\\"  (default)
""" + "empty = \n"  # a value set empty: nothing after "= "


def test_reads_set_and_commented_lines():
    options = apps.parse_print_config(PRINTED)
    assert options["domain"] == "2.6e-3,0.5e-3,1.2e-3"
    assert options["allow-lost"] == "0"
    assert options["material.density"] == "8900"
    assert options["recoater.tool"] == ""
    assert options["empty"] == ""


def test_reads_quoted_values():
    options = apps.parse_print_config(PRINTED)
    assert options["psd"] == "mono:d=30e-6 #x"
    assert options["fines.scaling"] == 'a  (b"\\'


def test_skips_the_header_and_comments_that_are_no_option():
    options = apps.parse_print_config(PRINTED + "# a remark = not an option\n")
    assert len(options) == 7


def test_refuses_a_key_given_twice():
    with pytest.raises(ValueError, match="bed"):
        apps.parse_print_config("bed = a.h5\nbed = b.h5\n")


def test_option_args():
    assert apps.option_args({"recoater.gap": "1e-4", "effects.drag": "false"}) == [
        "--recoater.gap", "1e-4", "--effects.drag", "false"]


def test_the_dosed_build_spread_is_what_deposit_resolves():
    """The words the studies give build's spreads to dose them, given to this build's deposit
    on the build's spread scene: the dose replaces the count, in the longer region, with the
    chamber's wall; and the pages print the same words."""
    words = shlex.split(apps.dosed_build_spread(2))
    options = apps.resolved_options("deposit", ["--config", apps.scene("spread-blade.ini"), *words])
    assert float(options["supply.dosing"]) == 2
    assert options["supply.count"] == "0"
    assert float(options["supply.x1"]) == 0.9e-3
    assert options["recoater.chamber"] == "true"
    assert apps.dosed_build_text(2) == (" --dosing 2", f' --spread-args "{apps.dosed_build_spread(2)}"')
    assert apps.dosed_build_text(None) == ("", "")
