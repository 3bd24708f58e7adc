"""help() documents the module: every public function and class has a docstring, and every
field of a bound struct its unit or meaning (what pydoc shows under "Data descriptors")."""
import pydoc

import powderbed


def public():
    return [(name, getattr(powderbed, name)) for name in powderbed.__all__ if name != "__version__"]


def test_every_public_function_and_class_has_a_docstring():
    undocumented = [name for name, value in public() if callable(value) and not (value.__doc__ or "").strip()]
    assert undocumented == []


def test_every_field_of_a_bound_struct_is_documented():
    structs = [value for _, value in public() if isinstance(value, type) and hasattr(value, "_fields")]
    assert len(structs) >= 15
    bare = [f"{s.__name__}.{f}" for s in structs for f in s._fields if not (getattr(s, f).__doc__ or "").strip()]
    assert bare == []


def test_help_shows_the_run_functions_arguments_and_the_structs_fields():
    text = pydoc.render_doc(powderbed.deposit, renderer=pydoc.plaintext)
    assert "deposit(bed, scene=None, settings=None, *, progress=None, **fields)" in text
    assert "progress(p) is called" in text
    text = pydoc.render_doc(powderbed.SinterScene, renderer=pydoc.plaintext)
    assert "spot_radius" in text and "w, m" in text
    assert powderbed.__version__.count(".") == 2
