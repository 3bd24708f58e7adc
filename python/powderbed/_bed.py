"""The Bed class: a bed's arrays and attributes as the C++ bed library reads them."""
import numpy as np

_ARRAYS = ("x", "y", "z", "r", "id", "material", "vx", "vy", "vz", "temperature", "phase")


class Bed:
    """Particles as numpy arrays: x, y, z, r (m), id; material, vx, vy, vz (m/s), temperature (K)
    and phase are None when the file has none. domain: dimension, lower, upper (m), periodic
    (three bools); provenance: the file's attributes (created_by, command_line, rng_seed, stage,
    scene, and deposit's contact_*)."""

    def __init__(self, fields, source=""):
        for key in _ARRAYS:
            value = fields.get(key)
            setattr(self, key, None if value is None else np.asarray(value))
        self.domain = dict(fields["domain"])
        self.provenance = dict(fields.get("provenance", {}))
        self.source = source

    def __len__(self):
        return len(self.x)

    @property
    def velocity(self):
        """N x 3 velocities (m/s), or None."""
        return None if self.vx is None else np.column_stack([self.vx, self.vy, self.vz])

    def as_dict(self):
        out = {key: getattr(self, key) for key in _ARRAYS}
        out["domain"] = self.domain
        out["provenance"] = self.provenance
        return out

    def __repr__(self):
        return f"Bed({len(self)} particles, {self.domain['dimension']}D)"


def bed_of(value, what):
    """`value` if it is a Bed; InputError naming `what` otherwise."""
    if not isinstance(value, Bed):
        from ._checks import refuse
        refuse(what, value, "a powderbed.Bed, e.g. from read_bed")
    return value
