#!/usr/bin/python3
"""Plots a point field of a VTK file (a body's samples, e.g. last_shell.vts of `iga run`; VTK
XML with raw appended data as iga writes it, or legacy ASCII .vtk) along a line of constant coordinate, with the given positions marked (face seams of
a CAD tool): e.g. the contact pressure of data/plate_on_die.json across the seams between the
die's flat top and its fillets.

usage: plot_vtk_line.py FILE FIELD AXIS VALUE MARKS out.png
FIELD: a scalar point array (contact_pressure); AXIS: x or y, the coordinate plotted along; the
samples within 1e-3 of VALUE in the other coordinate are used; MARKS: positions along AXIS
separated by ',' (or '-' for none).
  plot_vtk_line.py out/last_shell.vts contact_pressure x 0 -1.5,1.5 pressure_x.png
"""
import re
import struct
import sys

from plot_common import save


def read_vtk_xml(path, field):
    """(points, values) of the scalar point array `field` of a VTK XML file with raw appended
    data and UInt64 block headers (iga/output/vtk_xml_writer.hpp)."""
    data = open(path, "rb").read()
    start = data.find(b'<AppendedData encoding="raw">')
    if start < 0:
        sys.exit(f"{path}: not a VTK XML file with raw appended data")
    base = data.index(b"_", start) + 1
    arrays = {}
    for m in re.finditer(rb'<DataArray type="Float64"(?: Name="(\w+)")? NumberOfComponents="(\d+)"'
                         rb' format="appended" offset="(\d+)"/>', data[:start]):
        at = base + int(m.group(3))
        (size,) = struct.unpack_from("<Q", data, at)
        values = struct.unpack_from(f"<{size // 8}d", data, at + 8)
        arrays[(m.group(1) or b"Points").decode()] = (int(m.group(2)), values)
    if field not in arrays or arrays[field][0] != 1:
        sys.exit(f"{path}: no scalar point array {field}")
    flat = arrays["Points"][1]
    points = [list(flat[3 * i:3 * i + 3]) for i in range(len(flat) // 3)]
    return points, list(arrays[field][1])


def read_vtk(path, field):
    """(points, values) of the scalar point array `field` of a VTK file: XML (.vts, .vtu) or
    legacy ASCII (SCALARS)."""
    if path.endswith((".vts", ".vtu")):
        return read_vtk_xml(path, field)
    lines = open(path).read().split("\n")

    def numbers(start, count):
        out = []
        k = start
        while len(out) < count:
            out += [float(t) for t in lines[k].split()]
            k += 1
        return out

    n = 0
    points, values = [], []
    for k, line in enumerate(lines):
        if line.startswith("POINTS "):
            n = int(line.split()[1])
            flat = numbers(k + 1, 3 * n)
            points = [flat[3 * i:3 * i + 3] for i in range(n)]
        elif line.startswith("SCALARS " + field + " "):
            values = numbers(k + 2, n)  # past LOOKUP_TABLE
    if not values:
        sys.exit(f"{path}: no point array {field}")
    return points, values


def main(src, field, axis, value, marks, dst):
    points, values = read_vtk(src, field)
    a, b = (0, 1) if axis == "x" else (1, 0)
    line = sorted((p[a], v) for p, v in zip(points, values) if abs(p[b] - float(value)) < 1e-3)
    if not line:
        sys.exit(f"{src}: no samples with {'y' if axis == 'x' else 'x'} = {value}")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8, 4))
    ax.plot([s for s, _ in line], [v for _, v in line], ".-", lw=1, ms=3, label=field)
    if marks != "-":
        for m in marks.split(","):
            ax.axvline(float(m), color="gray", ls="--", lw=0.8)
    ax.set_xlabel(axis)
    ax.set_ylabel(field)
    ax.set_title(f"{field} along {'y' if axis == 'x' else 'x'} = {value} (dashed: face seams)")
    ax.grid(alpha=0.3)
    save(fig, dst)


if __name__ == "__main__":
    if len(sys.argv) != 7:
        sys.exit(__doc__)
    main(*sys.argv[1:])
