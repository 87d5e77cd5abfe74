// Restart archives (state_archive.hpp): sections of native binary values.
#include "iga/core/state_archive.hpp"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace iga {

namespace {
constexpr char kMagic[] = "iga-contact restart 1\n";  // format and version
constexpr std::uint32_t kSectionMark = 0x5EC71011u;
}  // namespace

StateArchive StateArchive::writer() {
  StateArchive a;
  a.data_.assign(kMagic, kMagic + sizeof kMagic - 1);
  return a;
}

StateArchive StateArchive::file_writer(const std::string& path) {
  StateArchive a;
  a.out_path_ = path;
  a.out_ = std::make_unique<std::ofstream>(path + ".part", std::ios::binary | std::ios::trunc);
  if (!*a.out_) throw RestartError(path + ": cannot write the restart file");
  a.out_->write(kMagic, sizeof kMagic - 1);
  return a;
}

StateArchive StateArchive::reader(const std::string& path) {
  StateArchive a;
  a.loading_ = true;
  a.file_ = path;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw RestartError(path + ": cannot read the restart file");
  a.data_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  const std::size_t m = sizeof kMagic - 1;
  if (a.data_.size() < m || std::memcmp(a.data_.data(), kMagic, m) != 0)
    throw RestartError(path + ": not a restart file of this program (version 1)");
  a.pos_ = m;
  return a;
}

void StateArchive::fail(const std::string& what) const {
  throw RestartError((file_.empty() ? std::string("restart state") : file_) + ", section \"" +
                     current_ + "\": " + what);
}

void StateArchive::raw(void* p, std::size_t n) {
  if (!loading_) {
    const auto* c = static_cast<const char*>(p);
    if (out_)
      out_->write(c, static_cast<std::streamsize>(n));
    else
      data_.insert(data_.end(), c, c + n);
    return;
  }
  if (data_.size() - pos_ < n) fail("the file ends early (truncated, or of another model)");
  std::memcpy(p, data_.data() + pos_, n);
  pos_ += n;
}

void StateArchive::section(const std::string& name) {
  std::uint32_t mark = kSectionMark;
  std::string s = name;
  if (!loading_) {
    current_ = name;
    raw(&mark, sizeof mark);
    io(s);
    return;
  }
  raw(&mark, sizeof mark);
  if (mark != kSectionMark) fail("expected the section \"" + name + "\" here");
  io(s);
  if (s != name) fail("expected the section \"" + name + "\", found \"" + s + "\"");
  current_ = name;
}

void StateArchive::io(double& x) {
  raw(&x, sizeof x);
}

void StateArchive::io(int& x) {
  std::int64_t v = x;
  raw(&v, sizeof v);
  x = static_cast<int>(v);
}

void StateArchive::io(bool& x) {
  char c = x ? 1 : 0;
  raw(&c, 1);
  if (loading_ && c != 0 && c != 1) fail("a flag that is neither 0 nor 1");
  x = c == 1;
}

void StateArchive::io(std::string& x) {
  std::int64_t n = static_cast<std::int64_t>(x.size());
  raw(&n, sizeof n);
  if (loading_) {
    if (n < 0 || static_cast<std::size_t>(n) > data_.size() - pos_)
      fail("a string longer than the rest of the file");
    x.assign(data_.data() + pos_, static_cast<std::size_t>(n));
    pos_ += static_cast<std::size_t>(n);
    return;
  }
  raw(x.data(), x.size());
}

void StateArchive::io(Eigen::VectorXd& x) {
  std::int64_t n = x.size();
  raw(&n, sizeof n);
  if (loading_) {
    if (n < 0 || static_cast<std::size_t>(n) > (data_.size() - pos_) / sizeof(double))
      fail("a vector longer than the rest of the file");
    x.resize(static_cast<Eigen::Index>(n));
  }
  if (n > 0) raw(x.data(), static_cast<std::size_t>(n) * sizeof(double));
}

void StateArchive::io(std::vector<double>& x) {
  // as a VectorXd: the same bytes
  Eigen::VectorXd v =
      Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size()));
  io(v);
  x.assign(v.data(), v.data() + v.size());
}

void StateArchive::finish() const {
  if (loading_ && pos_ != data_.size())
    fail(std::to_string(data_.size() - pos_) +
         " bytes left unread after the last section (a restart file of another model)");
}

void StateArchive::save(const std::string& path) {
  namespace fs = std::filesystem;
  const std::string tmp = path + ".part";
  if (out_) {
    if (path != out_path_)
      throw RestartError(path + ": this archive writes " + out_path_ + ", not this file");
    out_->close();
    const bool ok = !out_->fail();
    out_.reset();
    if (!ok) throw RestartError(path + ": writing the restart file failed");
  } else {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw RestartError(path + ": cannot write the restart file");
    out.write(data_.data(), static_cast<std::streamsize>(data_.size()));
    out.flush();
    if (!out) throw RestartError(path + ": writing the restart file failed");
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) throw RestartError(path + ": cannot replace the restart file: " + ec.message());
}

}  // namespace iga
