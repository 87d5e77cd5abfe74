#!/usr/bin/env python3
"""Writes the seed corpus of the model fuzz targets (fuzz/fuzz_loader.cpp, fuzz/fuzz_pipeline.cpp):
a coarse variant of every model of data/ and tests/data/models/ in fuzz/seeds/models/, the same
sections, entity, body, load, condition, contact and solver kinds, with few elements, few steps
and small files (each under 4 KB, the -max_len of scripts/fuzz.sh), so that one execution takes
milliseconds under the sanitizers and libFuzzer mutates what the loader knows rather than spend
its time on large models.
  scripts/fuzz_seeds.py          rewrite fuzz/seeds/models/ (commit the result)
  scripts/fuzz_seeds.py --check  exit 1 if a seed is missing, stale or too large
Coarsening: descriptions dropped (the top-level one names the source), numbers rounded to 6
significant digits, construction elements <= 4 (surfaces: subdivide <= 2, elevate <= 1),
contact points per element <= 2 (per direction <= 3), solver steps t_end / 2 (max_steps 4,
max_iterations <= 10, one hit time), plot references cut to 2 points, plots of reaction
columns dropped (the coarse bodies lack those control points). data/slit_annular_plate.json
(an explicit 35 x 7 NURBS annulus, 30 KB) gets a flat 2 x 2 plate instead, its loads, conditions
and solver keys kept.
"""
import json
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
OUT = ROOT / "fuzz" / "seeds" / "models"
MAX_BYTES = 4096


def small(x, cap):
    if isinstance(x, bool) or not isinstance(x, (int, list)):
        return x
    if isinstance(x, list):
        return [small(e, cap) for e in x]
    return min(x, cap)


def round_numbers(j):
    if isinstance(j, float):
        r = float(f"{j:.6g}")
        return int(r) if r.is_integer() and abs(r) < 1e15 else r
    if isinstance(j, list):
        return [round_numbers(e) for e in j]
    if isinstance(j, dict):
        return {k: round_numbers(v) for k, v in j.items()}
    return j


def strip_descriptions(j):
    if isinstance(j, list):
        return [strip_descriptions(e) for e in j]
    if isinstance(j, dict):
        return {k: strip_descriptions(v) for k, v in j.items()
                if not (k == "description" and isinstance(v, str))}
    return j


def coarsen_geometry(g):
    for e in g.values():
        if not isinstance(e, dict):
            continue
        if "elements" in e:
            e["elements"] = small(e["elements"], 4)
        if "arc_elements" in e:
            e["arc_elements"] = small(e["arc_elements"], 4)
        if "span_elements" in e:
            e["span_elements"] = small(e["span_elements"], 1)
        r = e.get("refine")
        if isinstance(r, dict):
            if "subdivide" in r:
                r["subdivide"] = small(r["subdivide"], 2)
            if "elevate" in r:
                r["elevate"] = small(r["elevate"], 1)


def coarsen(src, d):
    rel = src.relative_to(ROOT).as_posix()
    d = strip_descriptions(d)
    if "geometry" in d:
        coarsen_geometry(d["geometry"])
    if src.name == "slit_annular_plate.json":
        d["geometry"] = {"plate": {"type": "construction", "shape": "plane", "origin": [0, 0, 0],
                                   "du": [1, 0, 0], "dv": [0, 1, 0],
                                   "refine": {"elevate": 1, "subdivide": 2}}}
    for c in d.get("contact", []):
        if "points_per_element" in c:
            c["points_per_element"] = small(c["points_per_element"], 2)
        if "points_per_direction" in c:
            c["points_per_direction"] = small(c["points_per_direction"], 3)
    s = d.get("solver")
    if isinstance(s, dict):
        t_end = s.get("t_end", 1)
        for k in ("initial_step", "max_step"):
            if k in s:
                s[k] = t_end / 2
        s["max_steps"] = 4
        s["max_iterations"] = min(s.get("max_iterations", 10), 10)
        if s.get("hit_times"):
            s["hit_times"] = s["hit_times"][:1]
    out_section = d.get("output", {})
    # a plot of a reaction column (R<point>_...) names a control point the coarse body lacks
    out_section["plots"] = [p for p in out_section.get("plots", [])
                            if not re.search(r"R\w*?\d+_", p.get("x", "") + p.get("y", ""))]
    if not out_section["plots"]:
        out_section.pop("plots")
    for p in out_section.get("plots", []):
        for r in p.get("reference", []):
            r["points"] = r["points"][:2]
    d = round_numbers(d)
    out = {k: d[k] for k in ("format", "version", "name") if k in d}
    out["description"] = f"coarse fuzz seed of {rel} (scripts/fuzz_seeds.py)"
    out.update({k: v for k, v in d.items() if k not in out})
    return out


def seeds():
    sources = sorted((ROOT / "data").glob("*.json")) + sorted(
        (ROOT / "tests" / "data" / "models").glob("*.json"))
    for src in sources:
        d = coarsen(src, json.loads(src.read_text()))
        yield src.name, json.dumps(d, separators=(",", ":")) + "\n"


def main():
    check = "--check" in sys.argv[1:]
    OUT.mkdir(parents=True, exist_ok=True)
    status = 0
    expected = set()
    for name, text in seeds():
        expected.add(name)
        path = OUT / name
        if len(text) > MAX_BYTES:
            print(f"fuzz_seeds: {name}: {len(text)} bytes, above {MAX_BYTES}", file=sys.stderr)
            status = 1
        if check:
            if not path.exists() or path.read_text() != text:
                print(f"fuzz_seeds: {path.relative_to(ROOT)} is missing or stale", file=sys.stderr)
                status = 1
        else:
            path.write_text(text)
    for path in OUT.glob("*.json"):
        if path.name not in expected:
            print(f"fuzz_seeds: {path.relative_to(ROOT)} has no source model", file=sys.stderr)
            status = 1
    return status


if __name__ == "__main__":
    sys.exit(main())
