"""The body types as the core describes them: the one exported description (body_types.json, which the build writes
beside this package's modules in the devel and the install space from the C++ key tables). Every key's name, kind,
unit, range or choices (and what each choice sets: a roller's shape its inertia_factor), default, meaning, level and
whether a lesson page may change it; each type's state fields and its sweep column (name, label, unit); the world's
keys and the sweeps' energy_drift column. The .cfg files, the scripts and the web page read it here."""
from __future__ import annotations

import functools
import json
import os
import sys
from typing import Any, Dict, List, Optional, Sequence

FILE = "body_types.json"


def _candidates(extra: Sequence[str]) -> List[str]:
    import rigid_body_sim  # its __path__: the devel (or install) folder and, in devel, the source folder
    package_folders = list(getattr(rigid_body_sim, "__path__", []))  # getattr: Debian 11's mypy knows no __path__
    return [os.path.join(folder, FILE) for folder in [*extra, *package_folders]]


@functools.lru_cache(maxsize=None)
def load(*folders: str) -> Dict[str, Any]:
    """The description; `folders` are looked in first (a .cfg run by the build gets the devel Python folder)."""
    for path in _candidates(folders):
        if os.path.exists(path):
            with open(path, encoding="utf-8") as file:
                return dict(json.load(file))
    raise FileNotFoundError(f"{FILE} not found beside the rigid_body_sim package: build the package first")


def body_types() -> Dict[str, Any]:
    """Each type's description by its `type` name, in the order the core registers them."""
    return dict(load()["types"])


def keys(type_name: str) -> List[Dict[str, Any]]:
    return list(body_types()[type_name]["keys"])


def key(type_name: str, name: str) -> Optional[Dict[str, Any]]:
    return next((k for k in keys(type_name) if k["name"] == name), None)


def defaults(type_name: str) -> Dict[str, Any]:
    """The default of every key a config file writes."""
    return {k["name"]: k["default"] for k in keys(type_name) if k["written"]}


def units(type_name: str) -> Dict[str, str]:
    """The unit of each number key ("" for a pure number); text keys have none and are not listed."""
    return {k["name"]: k["unit"] for k in keys(type_name) if k["kind"] == "number"}


def lesson_keys() -> Dict[str, List[str]]:
    """The keys a lesson page may change, by type."""
    return {name: [k["name"] for k in t["keys"] if k["lesson"]] for name, t in body_types().items()}


def state_fields(type_name: str) -> List[str]:
    """A type's state fields, in the order of its CSV columns after t."""
    return [f["name"] for f in body_types()[type_name]["state_fields"]]


def reconfigure_generator(type_name: str) -> Any:
    """The dynamic_reconfigure generator of a type's server (its .cfg file): every key a config file writes,
    a number as a double and a text as a string (an enum of its choices), with its default, level and
    "meaning (unit)", and no range: the core's validation is the one range, so that a refusal names the value
    asked for (a server clamps into its own range before the node sees a request)."""
    from dynamic_reconfigure.parameter_generator_catkin import ParameterGenerator, double_t, str_t

    # Run by the build, a .cfg gets the devel Python folder of the package as its fourth argument.
    description = load(*sys.argv[4:5])["types"][type_name]
    gen = ParameterGenerator()
    for k in description["keys"]:
        if not k["written"]:
            continue
        meaning = k["meaning"] + (f" ({k['unit']})" if k["unit"] else "")
        if k["kind"] == "number":
            gen.add(k["name"], double_t, k["level"], meaning, float(k["default"]))
            continue
        choices = None
        if k["choices"]:
            choices = gen.enum([gen.const(c, str_t, c, c) for c in k["choices"]], k["name"])
        gen.add(k["name"], str_t, k["level"], meaning, k["default"], edit_method=choices or "")
    return gen
