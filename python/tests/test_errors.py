"""Every failure raises the documented error (README "Python", issue 36): InputError (a
ValueError) for a bad file or argument, ProgramError for a program that fails or prints no
summary, never TypeError, json.JSONDecodeError or UnicodeDecodeError."""
import os
import pathlib

import numpy as np
import pytest

import powderbed
from conftest import make_bed


def test_build_is_one_of_the_programs():
    assert "build" in powderbed.PROGRAMS
    with pytest.raises(powderbed.ProgramError, match="build exited 2") as error:
        powderbed.run("build", layers=1)  # no scene: refused by the program itself
    assert error.value.status == 2


def test_an_unknown_or_mistyped_program_is_an_input_error():
    for program in ("gromacs", 5, None, ["bedstat"]):
        with pytest.raises(powderbed.InputError, match="accepted: packgen"):
            powderbed.run(program)


def test_a_program_that_prints_no_json_raises_program_error(packed):
    path, _ = packed
    for options in ({"help": True}, {"print_config": True}):
        with pytest.raises(powderbed.ProgramError, match="printed no JSON summary") as error:
            powderbed.bedstat(path, **options)
        assert error.value.status == 0


def test_non_utf8_output_is_kept_as_escapes(tmp_path):
    # The program's message quotes the path, whose bytes are not UTF-8.
    name = os.fsencode(str(tmp_path)) + b"/caf\xe9.h5"
    with pytest.raises(powderbed.ProgramError, match=r"caf\\xe9\.h5") as error:
        powderbed.run("bedstat", os.fsdecode(name))
    assert error.value.status == 2


def test_binary_material_file_gives_one_printable_line(tmp_path, packed):
    path, _ = packed
    (tmp_path / "bin.csv").write_bytes(b"\x7fELF\x02\x01\x00\x00\x1b[31m,\xff\xfe\n\x01\n")
    with pytest.raises(powderbed.ProgramError, match=r"bin\.csv:1") as error:
        powderbed.run("keff", bed=path, material=tmp_path / "bin.csv", out=tmp_path / "k.h5")
    assert error.value.message.isprintable() and "\\x7fELF" in error.value.message


def test_option_values_of_the_wrong_type_are_input_errors(packed):
    path, _ = packed
    for value in ({"a": 1}, b"0,1e-5", [1e-5, None], object()):
        with pytest.raises(powderbed.InputError, match="bedstat: layer"):
            powderbed.bedstat(path, layer=value)
    with pytest.raises(powderbed.InputError, match="argument 1"):
        powderbed.bedstat({"not": "a path"})
    with pytest.raises(powderbed.InputError, match="NUL"):
        powderbed.bedstat(str(path) + "\0x")
    # Paths and numpy numbers are values the programs read as typed.
    summary = powderbed.bedstat(pathlib.Path(path), tol=np.float64(1e-6), profile=np.int64(2))
    assert len(summary["beds"]) == 1


@pytest.mark.parametrize("call, match", [
    (lambda: powderbed.read_bed(42), "read_bed: path"),
    (lambda: powderbed.read_bed(None), "read_bed: path"),
    (lambda: powderbed.read_bed("b.csv", domain=5), "read_bed: domain"),
    (lambda: powderbed.read_bed("b.csv", domain="0,0,0,1,1,1"), "read_bed: domain"),
    (lambda: powderbed.read_bed("b.csv", domain=(0, 0, 0, 1, 1)), "6 numbers"),
    (lambda: powderbed.write_bed({"x": [1.0]}, "b.h5"), "write_bed: bed"),
    (lambda: powderbed.sample_psd(5, 10), "sample_psd: spec"),
    (lambda: powderbed.sample_psd("mono:d=3e-5", -1), "sample_psd: n"),
    (lambda: powderbed.sample_psd("mono:d=3e-5", 2.5), "sample_psd: n"),
    (lambda: powderbed.sample_psd("mono:d=3e-5", "ten"), "sample_psd: n"),
    (lambda: powderbed.sample_psd("mono:d=3e-5", 10, seed=-1), "sample_psd: seed"),
    (lambda: powderbed.stats("a.h5"), "stats: bed"),
])
def test_bad_arguments_are_input_errors(call, match):
    with pytest.raises(powderbed.InputError, match=match):
        call()


def test_bad_stats_arguments_and_bed_fields_are_input_errors(tmp_path):
    bed = make_bed([1e-4], [1e-4], [1e-4], [1e-5], (1e-3, 1e-3, 1e-3))
    for options, match in (({"tol": "x"}, "stats: tol"), ({"tol": float("nan")}, "stats: tol"),
                           ({"layer": (0,)}, "stats: layer"), ({"profile": -1}, "stats: profile"),
                           ({"psd": 3}, "stats: psd")):
        with pytest.raises(powderbed.InputError, match=match):
            powderbed.stats(bed, **options)
    bed.domain["dimension"] = "three"
    with pytest.raises(powderbed.InputError, match="domain"):
        powderbed.write_bed(bed, tmp_path / "b.h5")
    del bed.domain["upper"]
    with pytest.raises(powderbed.InputError, match="domain"):
        powderbed.stats(bed)


def test_what_is_not_a_regular_file_is_an_input_error(tmp_path):
    os.mkfifo(tmp_path / "pipe.h5")
    with pytest.raises(powderbed.InputError, match="FIFO"):
        powderbed.read_bed(tmp_path / "pipe.h5")
    os.symlink("/dev/zero", tmp_path / "zero.csv")
    with pytest.raises(powderbed.InputError, match="character device"):
        powderbed.read_bed(tmp_path / "zero.csv", domain=(0, 0, 0, 1, 1, 1))
