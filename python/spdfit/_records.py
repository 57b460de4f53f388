"""The classes of the results the library renders as JSON (the physical fits, the payload, the
repairs of inertias, the physical experiment): each is a dict of its JSON's keys (so code written
for the dicts of earlier versions runs unchanged, and json.dumps takes it) whose keys are also its
attributes, read-only: ``est.mass`` is ``est["mass"]``. Nested objects are records too
(``fit.body[0].mass``). They pickle with a format number, and a pickle of another format is refused
with a message, as the library's other results are."""
import json as _json
import math as _math
import pickle as _pickle

import numpy as _np

# The pickle format of these classes; a state of another format is refused (pickle.hpp's rule).
_FORMAT = 1


class Record(dict):
    """A result of the library: a dict of its JSON's keys, each also a read-only attribute.

    Keys that are not identifiers (a method's name such as "spd-tls") are read as items only.
    to_json() writes the JSON the command line writes (arrays as lists, NaN and +-inf as null)."""

    __slots__ = ()

    def __init__(self, items=(), /):
        super().__init__(items)

    def __getattr__(self, name):
        try:
            return self[name]
        except KeyError:
            raise AttributeError(f"{type(self).__name__} has no attribute {name!r}; its keys: "
                                 f"{', '.join(self)}") from None

    def __setattr__(self, name, value):
        raise AttributeError(f"{type(self).__name__}'s attributes are read-only (its items are a dict's: "
                             f"result[{name!r}] = ...)")

    def __dir__(self):
        return sorted(set(super().__dir__()) | {k for k in self if isinstance(k, str) and k.isidentifier()})

    def __repr__(self):
        shown = []
        for key, value in self.items():
            if isinstance(value, (bool, int, float, str)) or value is None:
                shown.append(f"{key}={value!r}")
            if len(shown) == 6:
                break
        more = ", ..." if len(shown) < len(self) else ""
        return f"{type(self).__name__}({', '.join(shown)}{more})"

    def __reduce__(self):
        return _restore, (type(self).__name__, _FORMAT, dict(self))

    def to_dict(self):
        """The plain JSON value: dicts and lists of numbers, strings, booleans and None."""
        return _plain(self)

    def to_json(self, indent=2):
        """The result as JSON text (non-finite numbers as null, as the command line writes them)."""
        return _json.dumps(_plain(self), indent=indent)


def _plain(value):
    if isinstance(value, dict):
        return {key: _plain(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(item) for item in value]
    if isinstance(value, _np.ndarray):
        return _plain(value.tolist())
    if isinstance(value, _np.generic):
        value = value.item()
    if isinstance(value, float) and not _math.isfinite(value):
        return None
    return value


def _doc(summary, module, name):
    """A record class's docstring: its summary, then what every record is, in the NumPy format."""
    return f"""{summary}

    A dict of the result's JSON keys, each also a read-only attribute (``r.key`` is ``r["key"]``);
    the library's functions make them, and code written for the dicts of earlier versions runs
    unchanged. See spdfit._records.Record for pickling, to_dict and to_json.

    Parameters
    ----------
    items : mapping or iterable of pairs, optional
        The keys and values.

    Raises
    ------
    TypeError
        items that are neither a mapping nor pairs.

    Examples
    --------
    >>> import {module}
    >>> r = {module}.{name}({{"mass": 2.0, "warnings": []}})
    >>> r.mass, r["warnings"]
    (2.0, [])
    """


class PhysicalEstimate(Record):
    __doc__ = _doc("spdfit.physical.identify's result (hexapod.identify(..., physical=True)[\"physical\"] too):\n"
                   "    the keys of ``spdfit hexapod identify --json``'s \"physical\" object.",
                   "spdfit.physical", "PhysicalEstimate")
    __slots__ = ()


class PhysicalDesign(Record):
    __doc__ = _doc("spdfit.physical.design's result: which parameters a hexapod's geometry determines.",
                   "spdfit.physical", "PhysicalDesign")
    __slots__ = ()


class InertiaRepair(Record):
    __doc__ = _doc("spdfit.physical.inertia_repair's result: the keys of ``spdfit inertia repair``'s JSON.",
                   "spdfit.physical", "InertiaRepair")
    __slots__ = ()


class UrdfLinkRepair(Record):
    __doc__ = _doc("One link of spdfit.physical.inertia_repair_urdf's list.",
                   "spdfit.physical", "UrdfLinkRepair")
    __slots__ = ()


class RegressFit(Record):
    __doc__ = _doc("spdfit.physical.regress's result: the keys of ``spdfit physical regress --json`` and report.",
                   "spdfit.physical", "RegressFit")
    __slots__ = ()


class PayloadEstimate(Record):
    __doc__ = _doc("spdfit.payload.identify's result: the keys of ``spdfit payload identify --json``, residuals\n"
                   "    and report.",
                   "spdfit.payload", "PayloadEstimate")
    __slots__ = ()


class PayloadDesign(Record):
    __doc__ = _doc("spdfit.payload.design's result: the keys of ``spdfit payload design --json`` and report.",
                   "spdfit.payload", "PayloadDesign")
    __slots__ = ()


class PhysicalExperiment(Record):
    __doc__ = _doc("spdfit.experiment.physical's result: the JSON of ``spdfit experiment physical --json``.",
                   "spdfit.experiment", "PhysicalExperiment")
    __slots__ = ()


_CLASSES = {cls.__name__: cls for cls in (Record, PhysicalEstimate, PhysicalDesign, InertiaRepair, UrdfLinkRepair,
                                          RegressFit, PayloadEstimate, PayloadDesign, PhysicalExperiment)}


def _restore(name, format_number, items):
    if format_number != _FORMAT or name not in _CLASSES:
        raise _pickle.UnpicklingError(
            f"cannot unpickle {name}: it was pickled by another version of spdfit (record format {format_number}); "
            f"this spdfit reads format {_FORMAT} only: recompute it, or unpickle it with the spdfit that pickled it")
    return _CLASSES[name](items)


def record(cls, value):
    """value (a dict from the library's JSON, its arrays already converted) as a cls, and every dict
    nested in it (in dicts and lists) as a Record."""
    return cls({key: _nested(item) for key, item in value.items()})


def _nested(value):
    if isinstance(value, Record):
        return value
    if isinstance(value, dict):
        return record(Record, value)
    if isinstance(value, list):
        return [_nested(item) for item in value]
    return value
