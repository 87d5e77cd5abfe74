"""Models and runs: the JSON model of docs/model_format.md as a Python object.

A Model is the model document (a dict, in file order). It is loaded from a file, built from a
dict, or built step by step (add_geometry, add_material, add_body, ...); set() changes one
entry with the semantics of the apps' --set option; save() writes it. run() builds the analysis
and runs it; its Result holds the steps table, the displacements, the contact points and the
sampled bodies as numpy arrays. Errors in the model raise ModelError, which names the file and
the JSON path (.pointer) of the bad value.
"""

import copy
import json
import os

import numpy as np

from . import _core
from ._core import ModelError

FORMAT = "iga-contact-model"
VERSION = 1

_NAMED = ("geometry", "materials", "bodies", "load_curves", "rigid_motions")
_LISTED = ("boundary_conditions", "loads", "contact")


def _geometry_entry(entity):
    """A geometry entry as a dict: dicts as given, geometry objects through the C++ writer."""
    if isinstance(entity, dict):
        return copy.deepcopy(entity)
    if isinstance(entity, (_core.NurbsCurve, _core.Surface)):
        return json.loads(_core._entity_json(entity))
    raise TypeError("entity: expected a dict or a geometry object (NurbsCurve, NurbsSurface, "
                    "Plane, ...), got " + type(entity).__name__)


def _json_text(value, what):
    try:
        return json.dumps(value, allow_nan=False)
    except (TypeError, ValueError) as e:
        raise TypeError(f"{what}: not JSON data ({e})") from None


class Model:
    """An analysis model (docs/model_format.md) held as its JSON document.

    Model(name, description) starts an empty model to be built step by step;
    Model.load(path) reads a file; Model.from_dict(d) takes a parsed document.
    The document is `model.doc`, a dict in file order; `file` names the model in messages
    and is the folder relative paths in it (CAD files) are taken from.
    """

    def __init__(self, name="", description="", file="<python>"):
        """An empty model: the header and an empty geometry section."""
        self.doc = {"format": FORMAT, "version": VERSION, "name": name,
                    "description": description, "geometry": {}}
        self.file = str(file)

    # ---- reading and writing -----------------------------------------------------------------
    @classmethod
    def load(cls, path):
        """Reads a model file (ModelError naming the file if it cannot be read or parsed)."""
        m = cls.__new__(cls)
        m.file = os.fspath(path)
        m.doc = json.loads(_core._read_model_text(m.file))
        return m

    @classmethod
    def from_dict(cls, doc, file="<dict>"):
        """A model from a parsed document (a copy is kept). TypeError if it is not JSON data."""
        if not isinstance(doc, dict):
            raise TypeError("doc: expected a dict, got " + type(doc).__name__)
        m = cls.__new__(cls)
        m.file = str(file)
        m.doc = json.loads(_json_text(doc, "doc"))
        return m

    def to_dict(self):
        """A deep copy of the document."""
        return copy.deepcopy(self.doc)

    def to_json(self):
        """The document as the project formats model files."""
        return _core._format_json(_json_text(self.doc, "model"), self.file)

    def save(self, path):
        """Writes the document (Model.load(path).to_dict() == to_dict() afterwards)."""
        text = self.to_json()
        with open(path, "w", encoding="utf-8") as f:
            f.write(text + "\n")

    def __eq__(self, other):
        return isinstance(other, Model) and self.doc == other.doc

    def __repr__(self):
        return f"Model({self.doc.get('name', '')!r}, file={self.file!r})"

    # ---- changing it ----------------------------------------------------------------------------
    def set(self, pointer, value):
        """Sets the entry at the JSON pointer (e.g. '/contact/0/mu') to a Python value, as the
        apps' --set /pointer=value: the pointer names an existing entry (replaced) or a new key
        of an existing object (added). ModelError for a malformed pointer or a missing parent;
        a misspelt key is refused when the model is checked or run (with the allowed keys)."""
        if not isinstance(pointer, str):
            raise TypeError("pointer: expected a str such as '/solver/t_end'")
        text = _core._apply_override(_json_text(self.doc, "model"), self.file,
                                     pointer + "=" + _json_text(value, pointer))
        self.doc = json.loads(text)
        return self

    def get(self, pointer):
        """The entry at the JSON pointer (KeyError if there is none)."""
        node = self.doc
        if pointer in ("", "/"):
            return copy.deepcopy(node)
        for raw in pointer.lstrip("/").split("/"):
            key = raw.replace("~1", "/").replace("~0", "~")
            if isinstance(node, list):
                if not key.isdigit() or int(key) >= len(node):
                    raise KeyError(pointer)
                node = node[int(key)]
            elif isinstance(node, dict) and key in node:
                node = node[key]
            else:
                raise KeyError(pointer)
        return copy.deepcopy(node)

    def geometry_object(self, name):
        """The geometry entity `name` as an object: a NurbsCurve, NurbsSurface or analytic
        surface (ModelError for an unknown name, a patch group or a trimmed CAD face)."""
        return _core._geometry_entity(self._text(), self._source(), name)

    def _named(self, section, name, entry):
        if not isinstance(name, str) or not name:
            raise TypeError(f"{section}: the name must be a non-empty str")
        entries = self.doc.setdefault(section, {})
        if name in entries:
            raise ValueError(f"{section}: '{name}' is already defined")
        entries[name] = json.loads(_json_text(entry, f"{section}/{name}"))
        return self

    def _listed(self, section, entry):
        self.doc.setdefault(section, []).append(json.loads(_json_text(entry, section)))
        return self

    def add_geometry(self, name, entity):
        """Adds a geometry entity: a dict as in the file, or a NurbsCurve, NurbsSurface or
        analytic surface object."""
        return self._named("geometry", name, _geometry_entry(entity))

    def add_material(self, name, **props):
        """Adds a material, e.g. add_material('rope', type='rod', EA=2.1e4, EI=1e-3)."""
        return self._named("materials", name, props)

    def add_body(self, name, **props):
        """Adds a body, e.g. add_body('rope', type='rod', curve='rope', material='rope')."""
        return self._named("bodies", name, props)

    def add_load_curve(self, name, **props):
        """Adds a load curve, e.g. add_load_curve('pull', type='piecewise_linear',
        points=[[0, 0], [1, 1]])."""
        return self._named("load_curves", name, props)

    def add_rigid_motion(self, name, **props):
        """Adds the motion of the rigid surface `name`, e.g. rotation={...}."""
        return self._named("rigid_motions", name, props)

    def add_boundary_condition(self, **props):
        """Appends a boundary condition, e.g. type='fix', body='rope', points='end'."""
        return self._listed("boundary_conditions", props)

    def add_load(self, **props):
        """Appends a load, e.g. type='point_force', body='rope', at='start', magnitude=10."""
        return self._listed("loads", props)

    def add_contact(self, **props):
        """Appends a contact pair, e.g. type='curve_to_rigid', body='rope', rigid='drum'."""
        return self._listed("contact", props)

    def solver(self, **props):
        """Sets entries of the solver section (created if missing)."""
        self.doc.setdefault("solver", {}).update(json.loads(_json_text(props, "solver")))
        return self

    def output(self, **props):
        """Sets entries of the output section (created if missing)."""
        self.doc.setdefault("output", {}).update(json.loads(_json_text(props, "output")))
        return self

    # ---- checking and running ----------------------------------------------------------------
    def _text(self):
        return _json_text(self.doc, "model")

    def _source(self):
        # Relative paths in the model (CAD files) are taken from the model file's folder.
        return self.file

    def check(self):
        """Builds the analysis without running it: ModelError for any bad input. Returns a
        one-line description (bodies, unknowns, contact)."""
        return _core._Analysis(self._text(), self._source()).describe()

    def run(self, out=None, on_step=None, log=False, restart=None):
        """Runs the model and returns its Result.

        out: a folder for the usual outputs (steps.csv, summary.json, ParaView files,
        restart.bin), or None for none. on_step(row): called after each converged step with
        the step's row of the steps table (a dict column -> number); returning False stops
        the run (status 'stopped'); an exception in it ends the run and is raised again after
        the results so far are kept. log: print the progress lines. restart: a restart file of
        an earlier run of this model to continue."""
        if on_step is not None and not callable(on_step):
            raise TypeError("on_step: expected a callable or None")
        analysis = _core._Analysis(self._text(), self._source())
        result = Result(analysis)
        if out is not None:
            os.makedirs(out, exist_ok=True)
            with open(os.path.join(out, "model_used.json"), "w", encoding="utf-8") as f:
                f.write(self.to_json() + "\n")
        result._run(os.fspath(out) if out is not None else "", on_step, bool(log),
                    os.fspath(restart) if restart is not None else "")
        return result


class Result:
    """The analysis of a model after a run: its status and its results as numpy arrays.

    status, message, t (the last converged pseudo-time), num_steps, ... come from the solver;
    steps is the steps table (steps.csv) as a dict column -> array; displacements(body),
    sample(body), contact_points(pair) give the state of the last converged step."""

    def __init__(self, analysis):
        self._a = analysis
        self.info = {}

    def _run(self, out, on_step, log, restart):
        try:
            self.info = self._a.run(out, on_step, log, restart)
        except BaseException:
            self.info = {"status": "failed"}
            raise

    def __getattr__(self, key):
        info = self.__dict__.get("info", {})
        if key in info:
            return info[key]
        raise AttributeError(key)

    def __repr__(self):
        return (f"Result(status={self.info.get('status')!r}, t={self.info.get('t')}, "
                f"steps={self.info.get('steps')})")

    @property
    def converged(self):
        """Whether the run reached its end time (or stopped at full slip as its model asks)."""
        return self.info.get("status") == "converged" or (
            self.info.get("full_slip", False) and self.info.get("status") == "stopped")

    @property
    def num_steps(self):
        """The number of converged steps."""
        return self.info.get("steps", 0)

    @property
    def steps(self):
        """The steps table: column -> (number of steps,) float array, in steps.csv's order."""
        return self._a.steps()

    @property
    def columns(self):
        """The columns of the steps table (steps.csv), in order."""
        return list(self._a.columns)

    @property
    def body_names(self):
        """The bodies' names, in the model's order."""
        return list(self._a.body_names)

    @property
    def body_types(self):
        """The bodies' types ('rod', 'shell'), in the model's order."""
        return list(self._a.body_types)

    @property
    def pair_names(self):
        """The contact pairs' names (their columns in the steps table), in order."""
        return list(self._a.pair_names)

    def describe(self):
        """One line: the bodies, unknowns, contact and pseudo-time span."""
        return self._a.describe()

    def displacements(self, body=0):
        """Displacements of the body's control points, (n, 3), at the last converged step."""
        return self._a.displacements(body)

    def sample(self, body=0, samples=0):
        """The body sampled at `samples` points per element (and direction; 0: its default):
        a dict with points (n, 3), params (n, 2), elements (n,), shape and fields (name ->
        (n,) or (n, 3) array: a rod's axial force and curvature, a shell's displacement and
        stress resultants, the contact fields of its pairs)."""
        return self._a.sample(body, int(samples))

    def contact_points(self, pair=0):
        """The active contact points of a pair at the last converged step: a dict with points
        (n, 3) and fields (name -> array: gap, pressure, tractions, stick or slip state)."""
        return self._a.contact_points(pair)

    def write_output(self, folder, stem="state"):
        """Writes the ParaView files of the last converged state in the model's field format
        ("output": {"field_format": "vtk_xml"} by default: .vts grids and .vtu lines and points;
        "vtk": legacy .vtk files); returns their names, relative to `folder`."""
        os.makedirs(folder, exist_ok=True)
        return self._a.write_output(os.fspath(folder), stem)

    def steps_array(self):
        """The steps table as one (steps, columns) array, in the order of `columns`."""
        table = self.steps
        return np.column_stack([table[c] for c in self.columns]) if table else np.zeros((0, 0))
