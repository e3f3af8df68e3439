"""Deterministic mutations of the verification problems' scenes, for test_mutated_scenes.py.

A base is a problem's scene with the problem's own `overrides` applied (problems that share
a scene and overrides share a base); data files it names are made absolute, so that a mutant
written anywhere still finds them. Each base is walked for sites: every value (numbers, strings,
booleans, array elements), every array, every key of every table, every table. Each site gets
the mutations of its kind (MUTATIONS). Of all (mutation, key pattern) pairs, where the pattern
is the key path without indices (block[].vertices[][]), at most PER_PATTERN cases are kept,
those with the smallest hash of SEED and their id (the environment variable
VDEC_MUTANTS_PER_PATTERN of test_mutated_scenes.py changes the number, "all" keeps all): every key of every scene meets every
mutation that applies to it, the selection does not depend on the order of the files, and a new
scene changes only the picks of the patterns it shares.
"""
import copy
import hashlib
import json
import math
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

PROBLEMS = Path(__file__).resolve().parents[2] / "verification" / "problems"
SEED = "vdec-mutated-scenes-1"
PER_PATTERN = 8
UNKNOWN_KEY = "vdec_unknown_key"
_DELETE = object()

# Mutation name -> the replacement value, from the old one. By site kind.
NUMBER_MUTATIONS = {
    "nan": lambda v: math.nan,
    "inf": lambda v: math.inf,
    "-inf": lambda v: -math.inf,
    "huge": lambda v: 1e308,
    "negative": lambda v: -abs(v) if v else (-1 if isinstance(v, int) else -1.0),
    "zero": lambda v: 0 if isinstance(v, int) else 0.0,
    "int-overflow-32": lambda v: 4294967296,
    "wrong-type": lambda v: "text",
}
STRING_MUTATIONS = {"wrong-type": lambda v: 1.0, "empty-string": lambda v: ""}
BOOLEAN_MUTATIONS = {"wrong-type": lambda v: "true"}
ARRAY_MUTATIONS = {"empty-array": lambda v: [], "wrong-type": lambda v: 1.0}
TABLE_MUTATIONS = {"wrong-type": lambda v: 1, "unknown-key": lambda v: {**v, UNKNOWN_KEY: 1.0}}
KEY_MUTATIONS = {"missing-key": lambda v: _DELETE}
MUTATION_CLASSES = sorted({*NUMBER_MUTATIONS, *STRING_MUTATIONS, *BOOLEAN_MUTATIONS, *ARRAY_MUTATIONS,
                           *TABLE_MUTATIONS, *KEY_MUTATIONS})


@dataclass
class Base:
    name: str                 # the first problem (by id) that runs it
    scene: Path
    overrides: list
    document: dict = field(repr=False)


@dataclass
class Mutant:
    base: Base
    path: tuple               # keys and indices from the root
    mutation: str
    replace: object = field(repr=False)  # old value -> new value, or _DELETE

    @property
    def id(self):
        return f"{self.base.name}:{path_text(self.path)}:{self.mutation}"

    def document(self):
        doc = copy.deepcopy(self.base.document)
        if not self.path:
            return self.replace(doc)
        *parents, last = self.path
        node = doc
        for key in parents:
            node = node[key]
        new = self.replace(node[last])
        if new is _DELETE:
            del node[last]
        else:
            node[last] = new
        return doc


def path_text(path):
    text = ""
    for key in path:
        text += f"[{key}]" if isinstance(key, int) else (f".{key}" if text else key)
    return text


def named_key(mutant):
    """The key an error about the mutant must name, as vdec writes it: block[1].vertices for a
    point of a polygon, history[0].vdec_unknown_key for a key added to a table."""
    if mutant.mutation == "unknown-key":
        return f"{path_text(mutant.path)}.{UNKNOWN_KEY}" if mutant.path else UNKNOWN_KEY
    path = list(mutant.path)
    while path and isinstance(path[-1], int):
        path.pop()
    return path_text(path)


def pattern_text(path):
    return re.sub(r"\[\d+\]", "[]", path_text(path))


def _set_override(doc, text):
    """Applies one `--set key.path=value` (vdec's syntax, name[i] for the i-th table) to doc."""
    key_path, value = text.split("=", 1)
    node = doc
    parts = key_path.split(".")
    for part in parts[:-1]:
        match = re.fullmatch(r"(\w+)\[(\d+)\]", part)
        node = node[match[1]][int(match[2])] if match else node.setdefault(part, {})
    node[parts[-1]] = tomllib.loads("value = " + value)["value"]


def _absolute_data_files(node, folder):
    """Data files the scene names relative to its folder, made absolute (vdec joins the scene's
    folder with the name, and an absolute name stays itself)."""
    if isinstance(node, dict):
        for key, value in node.items():
            if isinstance(value, str) and value.endswith(".csv"):
                node[key] = str((folder / value).resolve())
            else:
                _absolute_data_files(value, folder)
    elif isinstance(node, list):
        for value in node:
            _absolute_data_files(value, folder)


def bases():
    """One Base per distinct (scene, problem overrides) among verification/problems."""
    found = {}
    for problem_file in sorted(PROBLEMS.glob("*/problem.toml")):
        problem = tomllib.loads(problem_file.read_text())
        scene = (problem_file.parent / problem["scene"]).resolve()
        overrides = list(problem.get("overrides", []))
        key = (scene, tuple(overrides))
        if key in found:
            continue
        document = tomllib.loads(scene.read_text())
        for text in overrides:
            _set_override(document, text)
        _absolute_data_files(document, scene.parent)
        found[key] = Base(problem["id"], scene, overrides, document)
    return list(found.values())


def _sites(node, path=()):
    """(path, mutations) for every site below node."""
    if isinstance(node, dict):
        yield path, TABLE_MUTATIONS if path else {"unknown-key": TABLE_MUTATIONS["unknown-key"]}
        for key, value in node.items():
            yield path + (key,), KEY_MUTATIONS
            yield from _sites(value, path + (key,))
    elif isinstance(node, list):
        if not (node and all(isinstance(v, dict) for v in node)):
            yield path, ARRAY_MUTATIONS
        for index, value in enumerate(node):
            yield from _sites(value, path + (index,))
    elif isinstance(node, bool):
        yield path, BOOLEAN_MUTATIONS
    elif isinstance(node, (int, float)):
        yield path, NUMBER_MUTATIONS
    elif isinstance(node, str):
        yield path, STRING_MUTATIONS


def _rank(case_id):
    return hashlib.sha256(f"{SEED}:{case_id}".encode()).hexdigest()


def all_mutants(selected_bases=None):
    """Every mutant of every base, before selection."""
    out = []
    for base in selected_bases if selected_bases is not None else bases():
        for path, mutations in _sites(base.document):
            for name, replace in mutations.items():
                out.append(Mutant(base, path, name, replace))
    return out


def selected_mutants(selected_bases=None, per_pattern=PER_PATTERN):
    """At most per_pattern mutants per (mutation, key pattern), by rank (None: all); in id order."""
    groups = {}
    for mutant in all_mutants(selected_bases):
        groups.setdefault((mutant.mutation, pattern_text(mutant.path)), []).append(mutant)
    chosen = []
    for group in groups.values():
        chosen += sorted(group, key=lambda m: _rank(m.id))[:per_pattern]
    return sorted(chosen, key=lambda m: m.id)


def _toml_key(key):
    return key if re.fullmatch(r"[A-Za-z0-9_-]+", key) else json.dumps(key)


def _toml_value(value):
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value)  # a TOML basic string
    if isinstance(value, list):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{_toml_key(k)} = {_toml_value(v)}" for k, v in value.items()) + "}"
    raise TypeError(f"no TOML for {value!r}")


def toml_text(document):
    """TOML for a scene document: top-level values, then [tables] and [[arrays of tables]],
    whose own sub-tables are written inline."""
    def is_tables(v):
        return isinstance(v, list) and v and all(isinstance(t, dict) for t in v)

    lines = [f"{_toml_key(k)} = {_toml_value(v)}" for k, v in document.items()
             if not isinstance(v, dict) and not is_tables(v)]
    for key, value in document.items():
        tables = [value] if isinstance(value, dict) else value if is_tables(value) else []
        for table in tables:
            lines.append(f"[{_toml_key(key)}]" if isinstance(value, dict) else f"[[{_toml_key(key)}]]")
            lines += [f"{_toml_key(k)} = {_toml_value(v)}" for k, v in table.items()]
    return "\n".join(lines) + "\n"
