// rigid_contact_iga._core, model: the JSON document's helpers (read a model file, apply a --set
// assignment, format) and an analysis built from a document, run with a per-step callback,
// with its results as numpy arrays. The package's Model class (model.py) is built on these.
//
// Notation: u the unknowns of all bodies at the last converged step, t its pseudo-time; a
// "sampled mesh" the points, parameters and named fields a body or a pair hands to a writer
// (iga/core/sampled_mesh.hpp).
#include <memory>
#include <optional>
#include <streambuf>
#include <type_traits>
#include <variant>

#include "iga/model/analysis.hpp"
#include "iga/model/model.hpp"
#include "python/src/py_common.hpp"

namespace iga::py {

namespace {

/// Lines written to it go to Python's sys.stdout (taking the GIL for each line).
class PythonLineBuf : public std::streambuf {
 public:
  ~PythonLineBuf() override {
    try {
      flush_line();
    } catch (...) {  // a destructor must not throw: the last partial line is lost
    }
  }

 protected:
  int overflow(int c) override {
    if (c == traits_type::eof()) return 0;
    line_.push_back(static_cast<char>(c));
    if (c == '\n') flush_line();
    return c;
  }
  int sync() override {
    flush_line();
    return 0;
  }

 private:
  void flush_line() {
    if (line_.empty()) return;
    pb::gil_scoped_acquire gil;
    pb::module_::import("sys").attr("stdout").attr("write")(line_);
    line_.clear();
  }
  std::string line_;
};

pb::dict mesh_dict(const SampledMesh& s) {
  pb::dict d;
  d["points"] = to_array(s.points);
  if (!s.params.empty()) {
    pb::array_t<double> p = new_array(static_cast<pb::ssize_t>(s.params.size()), 2);
    double* q = p.mutable_data();
    for (const auto& [a, b] : s.params) *q++ = a, *q++ = b;
    d["params"] = p;
    pb::array_t<int> e(std::vector<pb::ssize_t>{static_cast<pb::ssize_t>(s.elements.size())});
    std::copy(s.elements.begin(), s.elements.end(), e.mutable_data());
    d["elements"] = e;
  }
  d["shape"] = s.shape == SampledMesh::Shape::kGrid       ? pb::make_tuple(s.nu, s.nv)
               : s.shape == SampledMesh::Shape::kPolyline ? pb::make_tuple(s.points.size())
                                                          : pb::make_tuple();
  pb::dict fields;
  for (const auto& [name, v] : s.fields.scalars) fields[pb::str(name)] = to_array(v);
  for (const auto& [name, v] : s.fields.vectors) fields[pb::str(name)] = to_array(v);
  d["fields"] = fields;
  return d;
}

/// name(i) for i = 0 .. n-1.
template <class F>
std::vector<std::string> names(int n, F&& name) {
  std::vector<std::string> v;
  v.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) v.push_back(name(i));
  return v;
}

/// The index of a body or pair given by its number (IndexError out of range) or its name
/// (KeyError if there is none).
template <class F>
int index_of(const pb::object& which, int n, const std::string& what, F&& name) {
  if (pb::isinstance<pb::int_>(which)) {
    const int i = which.cast<int>();
    if (i < 0 || i >= n)
      throw pb::index_error(what + " " + std::to_string(i) + ": the model has " +
                            std::to_string(n) + " (" + what + " 0 .. " + std::to_string(n - 1) +
                            ")");
    return i;
  }
  const std::string key = which.cast<std::string>();
  for (int i = 0; i < n; ++i)
    if (name(i) == key) return i;
  throw pb::key_error("no " + what + " named '" + key + "'");
}

/// An analysis and the results of its last run.
class PyAnalysis {
 public:
  PyAnalysis(const std::string& text, const std::string& file)
      : a_(std::make_unique<Analysis>(Analysis::from_json(parse_json_text(text, file), file))) {
    u_ = VectorXd::Zero(a_->problem().num_dofs());
    columns_ = a_->csv_columns();
    t_ = a_->solver_settings().t0;
  }

  Analysis& a() { return *a_; }

  pb::dict run(const std::string& out_dir, const pb::object& on_step, bool log,
               const std::string& restart) {
    std::optional<pb::error_already_set> error;
    AnalysisStepCallback cb;
    if (!on_step.is_none()) {
      cb = [&](const VectorXd&, double, const AnalysisStep& st) {
        pb::gil_scoped_acquire gil;
        try {
          pb::dict row = step_dict(st);
          const pb::object r = on_step(row);
          return r.is_none() || r.cast<bool>();
        } catch (pb::error_already_set& e) {
          error.emplace(std::move(e));
          return false;
        }
      };
    }
    PythonLineBuf buf;
    std::ostream out(&buf);
    {
      pb::gil_scoped_release release;
      result_ = a_->run(log ? &out : nullptr, out_dir, cb, restart);
      out.flush();
    }
    u_ = result_.u;
    t_ = result_.solver.t;
    if (error) throw std::move(*error);  // the callback's own exception, after the run ended
    pb::dict d;
    d["status"] = to_string(result_.solver.status);
    d["message"] = result_.solver.message;
    d["t"] = result_.solver.t;
    d["steps"] = result_.solver.steps;
    d["cutbacks"] = result_.solver.cutbacks;
    d["newton_iterations"] = result_.solver.total_iterations;
    d["linear_steps"] = result_.solver.linear_steps;  // solved by the linear path
    d["assemblies"] = result_.solver.assemblies;
    d["load_rates"] = result_.solver.load_rates;  // arc length's dR/dt from the loads alone
    d["full_slip"] = result_.full_slip;
    d["seconds"] = result_.solver.time_total;
    d["restart_file"] = result_.restart_file;
    return d;
  }

  /// The steps table of the last run: column -> (steps,) array.
  pb::dict steps() const {
    const std::vector<std::string>& cols = columns_;
    std::vector<std::vector<double>> by(cols.size());
    for (std::size_t k = 0; k < result_.steps.size(); ++k) {
      const std::vector<double> v = a_->step_values(result_.steps[k].step, result_.steps[k]);
      for (std::size_t c = 0; c < cols.size() && c < v.size(); ++c) by[c].push_back(v[c]);
    }
    pb::dict d;
    for (std::size_t c = 0; c < cols.size(); ++c) d[pb::str(cols[c])] = to_array(by[c]);
    return d;
  }

  int body_index(const pb::object& body) const {
    return index_of(body, a_->num_bodies(), "body", [&](int b) { return a_->body_name(b); });
  }
  int pair_index(const pb::object& pair) const {
    return index_of(pair, a_->num_pairs(), "contact pair", [&](int k) { return a_->pair_name(k); });
  }

  VectorXd block(int b) const { return a_->problem().block(u_, b); }
  const std::vector<std::string>& columns() const { return columns_; }
  const VectorXd& u() const { return u_; }
  double t() const { return t_; }

 private:
  pb::dict step_dict(const AnalysisStep& st) const {
    const std::vector<std::string>& cols = columns_;
    const std::vector<double> v = a_->step_values(st.step, st);
    pb::dict d;
    for (std::size_t c = 0; c < cols.size() && c < v.size(); ++c) d[pb::str(cols[c])] = v[c];
    return d;
  }

  std::unique_ptr<Analysis> a_;
  std::vector<std::string> columns_;  ///< of steps.csv, fixed when the analysis is built
  AnalysisResult result_;
  VectorXd u_;
  double t_ = 0.0;
};

}  // namespace

void bind_model(pb::module_& m) {
  m.def(
      "_read_model_text", [](const std::string& path) { return read_json_file(path).dump(); },
      pb::arg("path"),
      "The model file as JSON text, in file order (ModelError naming the file when it cannot "
      "be read or parsed).");
  m.def(
      "_apply_override",
      [](const std::string& text, const std::string& file, const std::string& assignment) {
        Json doc = parse_json_text(text, file);
        apply_override(doc, file, assignment);
        return doc.dump();
      },
      pb::arg("text"), pb::arg("file"), pb::arg("assignment"));
  m.def(
      "_format_json",
      [](const std::string& text, const std::string& file) {
        return format_json(parse_json_text(text, file));
      },
      pb::arg("text"), pb::arg("file"));
  m.def(
      "_geometry_entity",
      [](const std::string& text, const std::string& file, const std::string& name) {
        const Model model = parse_model(parse_json_text(text, file), file);
        const GeometryEntity* e = model.geometry.find(name);
        if (!e) throw ModelError(file, "/geometry", "no geometric entity named '" + name + "'");
        return std::visit(
            [&](const auto& x) -> pb::object {
              using T = std::decay_t<decltype(x)>;
              if constexpr (std::is_same_v<T, PatchGroup> || std::is_same_v<T, TrimmedSurface>)
                throw ModelError(file, "/geometry/" + name,
                                 "a " + entity_type(*e) + ", not a curve or an untrimmed surface");
              else
                return pb::cast(std::make_shared<T>(x));
            },
            *e);
      },
      pb::arg("text"), pb::arg("file"), pb::arg("name"));
  m.def(
      "_check_model",
      [](const std::string& text, const std::string& file) {
        return model_to_json(parse_model(parse_json_text(text, file), file)).dump();
      },
      pb::arg("text"), pb::arg("file"),
      "Validates the geometry and the header; returns the document as the project writes it.");

  pb::class_<PyAnalysis>(m, "_Analysis")
      .def(pb::init<const std::string&, const std::string&>(), pb::arg("text"), pb::arg("file"))
      .def("describe", [](PyAnalysis& p) { return p.a().describe(); })
      .def_property_readonly("name", [](PyAnalysis& p) { return p.a().name(); })
      .def_property_readonly("body_names",
                             [](PyAnalysis& p) {
                               return names(p.a().num_bodies(),
                                            [&](int b) { return p.a().body_name(b); });
                             })
      .def_property_readonly("body_types",
                             [](PyAnalysis& p) {
                               return names(p.a().num_bodies(),
                                            [&](int b) { return p.a().body(b).type(); });
                             })
      .def_property_readonly("pair_names",
                             [](PyAnalysis& p) {
                               return names(p.a().num_pairs(),
                                            [&](int k) { return p.a().pair_name(k); });
                             })
      .def_property_readonly("columns", &PyAnalysis::columns)
      .def_property_readonly("num_dofs", [](PyAnalysis& p) { return p.a().problem().num_dofs(); })
      .def_property_readonly("t", &PyAnalysis::t)
      .def("run", &PyAnalysis::run, pb::arg("out_dir"), pb::arg("on_step"), pb::arg("log"),
           pb::arg("restart"))
      .def("steps", &PyAnalysis::steps)
      .def("displacements",
           [](PyAnalysis& p, const pb::object& body) {
             const int b = p.body_index(body);
             return to_array(p.a().body(b).control_point_displacements(p.block(b), p.t()));
           })
      .def("sample",
           [](PyAnalysis& p, const pb::object& body, int samples) {
             const int b = p.body_index(body);
             if (samples <= 0) samples = p.a().body(b).default_samples();
             return mesh_dict(p.a().body(b).sample(p.block(b), p.t(), samples));
           })
      .def("contact_points",
           [](PyAnalysis& p, const pb::object& pair) {
             return mesh_dict(p.a().pair(p.pair_index(pair)).points());
           })
      .def("write_output", [](PyAnalysis& p, const std::string& dir, const std::string& stem) {
        std::vector<std::string> files;
        for (const Analysis::OutputFile& f : p.a().write_output(dir, stem, p.u(), p.t()))
          files.push_back(f.file);
        return files;
      });
}

}  // namespace iga::py
