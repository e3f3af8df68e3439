"""The runs of a sweep: its parameters (from --set or a sweep file), the design that combines
their values (product, zip, or runs listed one by one), and the seeds of its realisations."""
import itertools
import json
import math
import tomllib
from dataclasses import dataclass, field

from vdec_sweep.errors import BAD_SET, EMPTY_VALUES, USAGE, SweepError


@dataclass(frozen=True)
class Parameter:
    key: str          # a scene key path, as vdec run --set takes it
    texts: tuple      # each value as TOML text, handed to vdec unchanged
    values: tuple     # each value as parsed, for the table and the plots


@dataclass
class SweepRun:
    index: int
    settings: dict                 # key -> TOML text of its value in this run
    values: dict                   # key -> parsed value
    seed: int = None               # the realisation's first region seed; None without --seeds
    overrides: list = field(default_factory=list)   # KEY=TEXT for vdec run --set, in order

    @property
    def name(self):
        return f"{self.index:04d}"


def toml_value(text):
    """The value of one TOML value text, or ValueError."""
    try:
        return tomllib.loads(f"value = {text}")["value"]
    except tomllib.TOMLDecodeError as e:
        raise ValueError(str(e)) from None


def toml_text(value):
    """TOML text of a value read from a sweep file, to pass to vdec run --set. The values a scene
    key can take (numbers, booleans, strings, arrays and tables of them) are few enough that a
    TOML writer is not worth a dependency; json.dumps writes strings with TOML's escapes."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return "nan" if math.isnan(value) else repr(value)
    if isinstance(value, (int, str)):
        return json.dumps(value)
    if isinstance(value, list):
        return "[" + ", ".join(toml_text(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{json.dumps(k)} = {toml_text(v)}" for k, v in value.items()) + "}"
    raise ValueError(f"{value!r} ({type(value).__name__}) cannot be a --set value")


def split_values(text):
    """V1,V2,... split at the commas outside brackets, braces and quotes, so that an array or a
    string holding commas stays one value."""
    values, depth, quote, start, k = [], 0, "", 0, 0
    while k < len(text):
        c = text[k]
        if quote:
            if c == "\\" and quote == '"':
                k += 1
            elif c == quote:
                quote = ""
        elif c in "\"'":
            quote = c
        elif c in "[{":
            depth += 1
        elif c in "]}":
            depth -= 1
        elif c == "," and depth == 0:
            values.append(text[start:k])
            start = k + 1
        k += 1
    values.append(text[start:])
    return [v.strip() for v in values]


def parse_set_option(text):
    """The Parameter of --set KEY=V1,V2,...; SweepError naming the option when malformed."""
    key, equals, rest = text.partition("=")
    key = key.strip()
    if not equals:
        raise SweepError(BAD_SET, f"--set '{text}': no '=': write --set KEY=V1,V2,...")
    if not key or any(c.isspace() for c in key):
        raise SweepError(BAD_SET, f"--set '{text}': '{key}' is not a scene key path")
    if not rest.strip():
        raise SweepError(EMPTY_VALUES, f"--set '{text}': no values after '='")
    texts = split_values(rest)
    values = []
    for position, value_text in enumerate(texts, start=1):
        if not value_text:
            raise SweepError(BAD_SET, f"--set '{text}': value {position} is empty")
        try:
            values.append(toml_value(value_text))
        except ValueError:
            raise SweepError(BAD_SET, f"--set '{text}': value {position} '{value_text}' is not a TOML value "
                                      f"(strings need quotes: 'KEY=\"a\",\"b\"')") from None
    return Parameter(key, tuple(texts), tuple(values))


def check_distinct(parameters, where):
    seen = set()
    for p in parameters:
        if p.key in seen:
            raise SweepError(BAD_SET, f"{where} '{p.key}' is given twice")
        seen.add(p.key)


def combine(parameters, design):
    """[(key -> (text, value))] of each run: every combination ("product", the first parameter
    varying slowest) or the i-th value of each ("zip", all parameters as long)."""
    if not parameters:
        return [{}]
    if design == "zip":
        lengths = {p.key: len(p.texts) for p in parameters}
        if len(set(lengths.values())) > 1:
            listed = ", ".join(f"{k} has {n}" for k, n in lengths.items())
            raise SweepError(BAD_SET, f"--design zip needs as many values for every --set: {listed}")
        rows = zip(*[zip(p.texts, p.values) for p in parameters])
    else:
        rows = itertools.product(*[list(zip(p.texts, p.values)) for p in parameters])
    return [{p.key: pair for p, pair in zip(parameters, row)} for row in rows]


def region_count(scene):
    """How many [[region]] tables the scene has: the seeds of a realisation go to each."""
    try:
        with open(scene, "rb") as f:
            regions = tomllib.load(f).get("region", [])
    except (OSError, tomllib.TOMLDecodeError) as e:
        raise SweepError(USAGE, f"--seeds: cannot read the scene {scene} to find its regions: {e}") from None
    return len(regions) if isinstance(regions, list) else 0


def seed_overrides(realisation, regions):
    """Realisation r (from 0) gives region i the seed r * regions + i + 1: each region of each
    realisation its own random stream, and realisation 0 of a one-region scene the default seed 1."""
    return [(i, realisation * regions + i + 1) for i in range(regions)]


def build_runs(combinations, seeds=None, regions=0):
    """The runs: each combination (dict key -> (text, value)), times each realisation if seeds."""
    runs = []
    for combination in combinations:
        for realisation in range(seeds or 1):
            overrides = [f"{key}={text}" for key, (text, _) in combination.items()]
            seed = None
            if seeds:
                pairs = seed_overrides(realisation, regions)
                overrides += [f"region[{i}].seed={s}" for i, s in pairs]
                seed = pairs[0][1]
            runs.append(SweepRun(len(runs), {k: t for k, (t, _) in combination.items()},
                                 {k: v for k, (_, v) in combination.items()}, seed, overrides))
    return runs


def check_seed_keys(keys, seeds):
    if seeds:
        for key in keys:
            if key.startswith("region[") and key.endswith("].seed"):
                raise SweepError(BAD_SET, f"--set '{key}' and --seeds both set the seeds: give one of them")
