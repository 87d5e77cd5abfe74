// The output meshes of a run spread over several processes; see mesh_parts.hpp.
#include "iga/output/mesh_parts.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <type_traits>

namespace iga {

namespace {

// Bytes in, bytes out: plain values and vectors of them, strings with their length.
class Writer {
 public:
  template <class T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  template <class T>
  void values(const std::vector<T>& v) {
    value(static_cast<long long>(v.size()));
    if (!v.empty()) out_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void text(const std::string& s) {
    value(static_cast<long long>(s.size()));
    out_ += s;
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

class Reader {
 public:
  explicit Reader(const std::string& in) : in_(in) {}
  template <class T>
  T value() {
    T v;
    need(sizeof v);
    std::memcpy(&v, in_.data() + at_, sizeof v);
    at_ += sizeof v;
    return v;
  }
  template <class T>
  std::vector<T> values() {
    const auto n = count();
    std::vector<T> v(n);
    need(n * sizeof(T));
    if (n > 0) std::memcpy(static_cast<void*>(v.data()), in_.data() + at_, n * sizeof(T));
    at_ += n * sizeof(T);
    return v;
  }
  std::string text() {
    const auto n = count();
    need(n);
    std::string s = in_.substr(at_, n);
    at_ += n;
    return s;
  }
  bool done() const { return at_ == in_.size(); }

 private:
  std::size_t count() {
    const auto n = value<long long>();
    if (n < 0) throw std::runtime_error("unpack_meshes: a negative length");
    return static_cast<std::size_t>(n);
  }
  void need(std::size_t n) const {
    if (n > in_.size() - at_) throw std::runtime_error("unpack_meshes: the bytes end early");
  }
  const std::string& in_;
  std::size_t at_ = 0;
};

bool same_fields(const PointFields& a, const PointFields& b) {
  if (a.scalars.size() != b.scalars.size() || a.vectors.size() != b.vectors.size()) return false;
  for (std::size_t k = 0; k < a.scalars.size(); ++k)
    if (a.scalars[k].first != b.scalars[k].first) return false;
  for (std::size_t k = 0; k < a.vectors.size(); ++k)
    if (a.vectors[k].first != b.vectors[k].first) return false;
  return true;
}

}  // namespace

std::string pack_meshes(const std::vector<MeshOutput>& meshes) {
  Writer w;
  w.value(static_cast<long long>(meshes.size()));
  for (const MeshOutput& o : meshes) {
    w.text(o.series);
    w.text(o.stem);
    w.text(o.title);
    const SampledMesh& m = o.mesh;
    w.value(static_cast<int>(m.shape));
    for (int v : {m.nu, m.nv, m.i0, m.j0}) w.value(v);
    w.values(m.points);
    w.values(m.params);
    w.values(m.elements);
    w.value(static_cast<long long>(m.fields.scalars.size()));
    for (const auto& [name, f] : m.fields.scalars) {
      w.text(name);
      w.values(f);
    }
    w.value(static_cast<long long>(m.fields.vectors.size()));
    for (const auto& [name, f] : m.fields.vectors) {
      w.text(name);
      w.values(f);
    }
  }
  return w.take();
}

std::vector<MeshOutput> unpack_meshes(const std::string& bytes) {
  Reader r(bytes);
  std::vector<MeshOutput> meshes(static_cast<std::size_t>(r.value<long long>()));
  for (MeshOutput& o : meshes) {
    o.series = r.text();
    o.stem = r.text();
    o.title = r.text();
    SampledMesh& m = o.mesh;
    const int shape = r.value<int>();
    if (shape < 0 || shape > static_cast<int>(SampledMesh::Shape::kGrid))
      throw std::runtime_error("unpack_meshes: an unknown mesh shape");
    m.shape = static_cast<SampledMesh::Shape>(shape);
    for (int* v : {&m.nu, &m.nv, &m.i0, &m.j0}) *v = r.value<int>();
    m.points = r.values<Eigen::Vector3d>();
    m.params = r.values<std::array<double, 2>>();
    m.elements = r.values<int>();
    for (auto n = r.value<long long>(); n > 0; --n) {
      std::string name = r.text();
      m.fields.scalars.emplace_back(std::move(name), r.values<double>());
    }
    for (auto n = r.value<long long>(); n > 0; --n) {
      std::string name = r.text();
      m.fields.vectors.emplace_back(std::move(name), r.values<Eigen::Vector3d>());
    }
  }
  if (!r.done()) throw std::runtime_error("unpack_meshes: bytes left over");
  return meshes;
}

namespace {

[[noreturn]] void join_fail(const std::string& stem, const std::string& why) {
  throw std::runtime_error("the output mesh " + stem + ": " + why);
}

// The fields of `from`'s point k appended to `to`'s, or written at point i (grids).
void copy_values(const PointFields& from, std::size_t k, PointFields& to, std::size_t i) {
  for (std::size_t f = 0; f < to.scalars.size(); ++f)
    to.scalars[f].second[i] = from.scalars[f].second[k];
  for (std::size_t f = 0; f < to.vectors.size(); ++f)
    to.vectors[f].second[i] = from.vectors[f].second[k];
}

// Points or a polyline: the parts one after the other.
void join_list(const std::vector<const SampledMesh*>& filled, SampledMesh& out) {
  for (const SampledMesh* m : filled) {
    out.points.insert(out.points.end(), m->points.begin(), m->points.end());
    out.params.insert(out.params.end(), m->params.begin(), m->params.end());
    out.elements.insert(out.elements.end(), m->elements.begin(), m->elements.end());
  }
  for (auto& f : out.fields.scalars) f.second.resize(out.points.size());
  for (auto& f : out.fields.vectors) f.second.resize(out.points.size());
  std::size_t i = 0;
  for (const SampledMesh* m : filled)
    for (std::size_t k = 0; k < m->points.size(); ++k) copy_values(m->fields, k, out.fields, i++);
}

// A grid: the whole's size from the parts' places; the parts written from the last rank to
// the first, so that the lower rank's value stands where they overlap.
void join_grid(const std::string& stem, const std::vector<const SampledMesh*>& filled,
               SampledMesh& out) {
  int nu = 0, nv = 0;
  for (const SampledMesh* m : filled) {
    if (m->nu * m->nv != static_cast<int>(m->points.size()) || m->i0 < 0 || m->j0 < 0)
      join_fail(stem, "a grid part whose size or place does not fit its points");
    nu = std::max(nu, m->i0 + m->nu);
    nv = std::max(nv, m->j0 + m->nv);
  }
  const auto n = static_cast<std::size_t>(nu) * static_cast<std::size_t>(nv);
  const bool with_params = !filled.front()->params.empty();
  out.nu = nu;
  out.nv = nv;
  out.points.assign(n, Eigen::Vector3d::Zero());
  if (with_params) {
    out.params.assign(n, {0.0, 0.0});
    out.elements.assign(n, -1);
  }
  for (auto& f : out.fields.scalars) f.second.assign(n, 0.0);
  for (auto& f : out.fields.vectors) f.second.assign(n, Eigen::Vector3d::Zero());
  std::vector<char> covered(n, 0);
  for (auto it = filled.rbegin(); it != filled.rend(); ++it) {
    const SampledMesh& m = **it;
    for (int j = 0; j < m.nv; ++j)
      for (int i = 0; i < m.nu; ++i) {
        const auto src = static_cast<std::size_t>(i + m.nu * j);
        const auto dst = static_cast<std::size_t>(m.i0 + i) +
                         static_cast<std::size_t>(nu) * static_cast<std::size_t>(m.j0 + j);
        covered[dst] = 1;
        out.points[dst] = m.points[src];
        if (with_params) {
          out.params[dst] = m.params[src];
          out.elements[dst] = m.elements[src];
        }
        copy_values(m.fields, src, out.fields, dst);
      }
  }
  if (std::find(covered.begin(), covered.end(), 0) != covered.end())
    join_fail(stem, "its grid parts leave holes in the whole grid");
}

}  // namespace

MeshOutput join_parts(std::vector<MeshOutput> parts) {
  if (parts.empty()) throw std::invalid_argument("join_parts: no parts");
  MeshOutput whole;
  whole.series = parts.front().series;
  whole.stem = parts.front().stem;
  whole.title = parts.front().title;
  std::vector<const SampledMesh*> filled;  // the parts with points, in rank order
  for (const MeshOutput& p : parts)
    if (!p.mesh.points.empty()) filled.push_back(&p.mesh);
  if (filled.empty()) {
    whole.mesh = std::move(parts.front().mesh);
    return whole;
  }
  const SampledMesh& first = *filled.front();
  const bool with_params = !first.params.empty();
  for (const SampledMesh* m : filled) {
    if (m->shape != first.shape || !same_fields(m->fields, first.fields))
      join_fail(whole.stem, "its parts from the processes differ in shape or fields");
    if (m->params.empty() == with_params ||
        (with_params &&
         (m->params.size() != m->points.size() || m->elements.size() != m->params.size())))
      join_fail(whole.stem, "its parts differ in their body parameters");
  }
  SampledMesh& out = whole.mesh;
  out.shape = first.shape;
  out.fields = first.fields;
  if (first.shape == SampledMesh::Shape::kGrid) {
    join_grid(whole.stem, filled, out);
  } else {
    if (first.shape == SampledMesh::Shape::kPolyline && filled.size() > 1)
      join_fail(whole.stem, "a polyline in parts on several processes");
    join_list(filled, out);
  }
  return whole;
}

}  // namespace iga
