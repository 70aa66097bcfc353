// Peer renderers in `ptlab converge`: spec parsing, the Python runner's process and protocol.
#include "tools/converge/peer_variant.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include <nlohmann/json.hpp>

extern char** environ;

namespace ptlab {
namespace {

constexpr const char* kRendererKeys = "renderer, variant, sampler, max_depth, rr_depth";
// The runner's exit statuses (tools/converge/peer/mitsuba_peer.py).
constexpr int kPeerExitInput = 2, kPeerExitNoMitsuba = 3;

bool ParseInt(const std::string& s, int lo, int* out) {
  const char* end = s.data() + s.size();
  const auto [ptr, ec] = std::from_chars(s.data(), end, *out);
  return ec == std::errc() && ptr == end && *out >= lo;
}

bool OneOf(const std::string& v, std::initializer_list<const char*> values) {
  for (const char* x : values)
    if (v == x) return true;
  return false;
}

std::string Number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

// A child process with its stdin and stdout on pipes; stderr is ours.
// The child's stdin is a socket so that a write after it died fails with EPIPE instead of
// raising SIGPIPE (send with MSG_NOSIGNAL).
struct Child {
  pid_t pid = -1;
  int in = -1;          // the child's stdin
  FILE* out = nullptr;  // the child's stdout

  Status Start(const std::vector<std::string>& argv) {
    int to_child[2], from_child[2];
    if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, to_child) != 0)
      return Status::Error(std::string("socketpair: ") + std::strerror(errno));
    if (pipe2(from_child, O_CLOEXEC) != 0) {
      close(to_child[0]), close(to_child[1]);
      return Status::Error(std::string("pipe: ") + std::strerror(errno));
    }
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, to_child[0], 0);
    posix_spawn_file_actions_adddup2(&actions, from_child[1], 1);
    for (const int fd : {to_child[0], to_child[1], from_child[0], from_child[1]})
      posix_spawn_file_actions_addclose(&actions, fd);
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    const int rc = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    close(to_child[0]), close(from_child[1]);
    if (rc != 0) {
      close(to_child[1]), close(from_child[0]);
      return Status::Error("cannot run " + argv[0] + ": " + std::strerror(rc));
    }
    in = to_child[1];
    out = fdopen(from_child[0], "r");
    return Status::Ok();
  }

  bool ReadLine(std::string* line) {
    line->clear();
    char buf[4096];
    while (std::fgets(buf, sizeof buf, out)) {
      *line += buf;
      if (!line->empty() && line->back() == '\n') return true;
    }
    return !line->empty();
  }

  bool Send(const std::string& word) {
    const std::string line = word + "\n";
    return send(in, line.data(), line.size(), MSG_NOSIGNAL) == ssize_t(line.size());
  }

  // Closes the pipes and waits; the exit status, or 128 + signal.
  int Finish() {
    if (in >= 0) close(in), in = -1;
    if (out) std::fclose(out), out = nullptr;
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }
};

std::string FilterArgs(const FilterDesc& f) {
  switch (f.type) {
    case FilterDesc::Type::kBox: return "box";
    case FilterDesc::Type::kTent: return "tent";
    case FilterDesc::Type::kGaussian: return "gaussian";
  }
  return "gaussian";
}

}  // namespace

bool IsPeerSpec(const std::string& spec) {
  size_t at = 0;
  while (at <= spec.size()) {
    size_t end = spec.find(',', at);
    if (end == std::string::npos) end = spec.size();
    if (spec.compare(at, 9, "renderer=") == 0) return true;
    at = end + 1;
  }
  return false;
}

StatusOr<PeerVariant> ParsePeerVariant(const std::string& spec) {
  PeerVariant v;
  bool has_renderer = false;
  std::vector<std::string> seen;
  size_t at = 0;
  while (at < spec.size()) {
    size_t end = spec.find(',', at);
    if (end == std::string::npos) end = spec.size();
    const std::string item = spec.substr(at, end - at);
    at = end + 1;
    const size_t eq = item.find('=');
    if (eq == std::string::npos || eq == 0)
      return Status::Error("variant '" + spec + "': '" + item + "' is not key=value (peer keys: " +
                           kRendererKeys + ")");
    const std::string key = item.substr(0, eq), value = item.substr(eq + 1);
    // A key given twice is ambiguous (the last one silently won): refused.
    if (std::find(seen.begin(), seen.end(), key) != seen.end())
      return Status::Error("variant '" + spec + "': peer key '" + key +
                           "' is given twice; expected each key at most once");
    seen.push_back(key);
    auto bad = [&](const char* expected) {
      return Status::Error("variant '" + spec + "': peer key '" + key + "': '" + value +
                           "' is not " + expected);
    };
    if (key == "renderer") {
      if (value != "mitsuba3") return bad("mitsuba3 (the one peer renderer so far)");
      has_renderer = true;
    } else if (key == "variant") {
      if (!OneOf(value, {"llvm_ad_rgb", "scalar_rgb"})) return bad("llvm_ad_rgb or scalar_rgb");
      v.mitsuba_variant = value;
    } else if (key == "sampler") {
      if (!OneOf(value, {"independent", "multijitter", "stratified", "ldsampler", "orthogonal"}))
        return bad("one of independent, multijitter, stratified, ldsampler, orthogonal");
      v.sampler = value;
    } else if (key == "max_depth") {
      if (!ParseInt(value, -1, &v.max_depth)) return bad("an integer >= -1 (-1: unbounded)");
      v.max_depth_given = true;
    } else if (key == "rr_depth") {
      if (!ParseInt(value, 1, &v.rr_depth)) return bad("an integer >= 1");
    } else {
      return Status::Error("variant '" + spec + "': unknown peer key '" + key +
                           "'; a renderer= variant takes " + kRendererKeys +
                           " (ptlab's own keys do not apply to a peer)");
    }
  }
  if (!has_renderer) return Status::Error("variant '" + spec + "': no renderer= key");
  return v;
}

std::string PeerPython() {
  if (const char* p = std::getenv("PTLAB_MITSUBA_PYTHON"); p && *p) return p;
  std::string cache;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) {
    cache = x;
  } else if (const char* h = std::getenv("HOME"); h && *h) {
    cache = std::string(h) + "/.cache";
  } else {
    cache = "/tmp";
  }
  return cache + "/ptlab/mitsuba-venv/bin/python";
}

PeerFilm::PeerFilm(int width, int height)
    : width_(width),
      height_(height),
      total_(size_t(width) * size_t(height) * 4, 0.0),
      half_{total_, total_} {}

void PeerFilm::Add(const PeerPass& pass) {
  const std::vector<float>& p = *pass.rgbw;
  std::vector<double>& half = half_[pass.index % 2];
  for (size_t i = 0; i < p.size() && i < total_.size(); ++i) {
    total_[i] += double(p[i]);
    half[i] += double(p[i]);
  }
}

Image PeerFilm::Resolve(const std::vector<double>& sums) const {
  Image image(width_, height_);
  for (size_t px = 0; px < size_t(width_) * size_t(height_); ++px) {
    const double w = sums[4 * px + 3];
    for (int c = 0; c < 3; ++c)
      image.rgb[3 * px + size_t(c)] = w > 0 ? float(sums[4 * px + size_t(c)] / w) : 0.0f;
  }
  return image;
}

Status RunPeer(const PeerVariant& variant, const PeerRunOptions& o,
               const std::function<void(const PeerPass&)>& on_pass, PeerSetup* setup,
               bool* interrupted) {
  namespace fs = std::filesystem;
  *interrupted = false;
  const std::string python = PeerPython();
  if (access(python.c_str(), X_OK) != 0)
    return Status::Error("Mitsuba 3 is not installed: no Python interpreter at " + python +
                         " (`./lab peer-install` makes that virtual environment with Mitsuba "
                         "from PyPI; or set PTLAB_MITSUBA_PYTHON)");
  const std::string script = std::string(PTLAB_SOURCE_DIR) + "/tools/converge/peer/mitsuba_peer.py";
  if (!fs::exists(script)) return Status::Error("the peer runner " + script + " is missing");
  const Scene& scene = *o.scene;
  const CameraDesc& cam = scene.camera;
  // The peer runner builds a perspective or thin-lens sensor from these arguments.
  if (cam.projection != CameraDesc::Projection::kPerspective)
    return Status::Error("the mitsuba3 peer renders perspective and thin-lens cameras; this "
                         "scene's camera is orthographic");
  // Mitsuba counts path vertices (2 = direct light), ptlab bounces (1 = direct light).
  const int max_depth = variant.max_depth_given          ? variant.max_depth
                        : scene.integrator.max_depth < 0 ? -1
                                                         : scene.integrator.max_depth + 1;
  std::string to_world;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      to_world += (to_world.empty() ? "" : ",") + Number(cam.camera_to_world.matrix().m[r][c]);
  std::vector<std::string> argv = {
      python, script, "--scene=" + o.scene_path, "--width=" + std::to_string(cam.width),
      "--height=" + std::to_string(cam.height), "--filter=" + FilterArgs(scene.filter),
      "--filter-radius=" + Number(scene.filter.radius),
      "--filter-stddev=" + Number(scene.filter.stddev), "--camera-to-world=" + to_world,
      "--fov=" + Number(cam.fov_deg), "--near=" + Number(cam.near_clip),
      "--far=" + Number(cam.far_clip), "--aperture=" + Number(cam.aperture_radius),
      "--focus=" + Number(cam.focus_distance), "--lookat=" + o.lookat,
      "--variant=" + variant.mitsuba_variant, "--sampler=" + variant.sampler,
      "--max-depth=" + std::to_string(max_depth),
      "--rr-depth=" + std::to_string(variant.rr_depth),
      "--pass-spp=" + std::to_string(o.pass_spp), "--spp=" + std::to_string(o.spp),
      "--time=" + Number(o.time), "--seed=" + std::to_string(o.seed),
      "--threads=" + std::to_string(o.threads), "--out=" + o.work_dir};
  Child child;
  PTLAB_RETURN_IF_ERROR(child.Start(argv));
  std::string line, error;
  std::vector<float> rgbw;
  bool done = false;
  while (child.ReadLine(&line)) {
    // The runner keeps its stdout for the protocol; should a library still print there, its
    // text goes to stderr, also when it ran into a protocol line without a newline.
    const size_t brace = line.find("{\"event\"");
    if (brace != std::string::npos && brace > 0) {
      std::fprintf(stderr, "%s\n", line.substr(0, brace).c_str());
      line.erase(0, brace);
    }
    nlohmann::json j = nlohmann::json::parse(line, nullptr, /*allow_exceptions=*/false);
    if (j.is_discarded() || !j.is_object() || !j.contains("event") || !j["event"].is_string()) {
      std::fprintf(stderr, "%s", line.c_str());
      continue;
    }
    const std::string event = j["event"].get<std::string>();
    if (event == "error") {
      error = j.value("message", std::string("unknown error"));
    } else if (event == "ready") {
      setup->version = "Mitsuba " + j.value("mitsuba", std::string("?")) + " (" +
                       j.value("variant", std::string("?")) + ")";
      setup->load_seconds = j.value("load_seconds", 0.0);
      setup->warmup_seconds = j.value("warmup_seconds", 0.0);
    } else if (event == "pass") {
      PeerPass pass;
      pass.index = j.value("pass", 0u);
      pass.spp_done = j.value("spp", 0u);
      pass.seconds = j.value("seconds", 0.0);
      pass.cpu_seconds = j.value("cpu_seconds", 0.0);
      pass.width = cam.width, pass.height = cam.height;
      const std::string file = j.value("file", std::string());
      rgbw.assign(size_t(cam.width) * size_t(cam.height) * 4, 0.0f);
      std::ifstream f(file, std::ios::binary);
      f.read(reinterpret_cast<char*>(rgbw.data()), std::streamsize(rgbw.size() * sizeof(float)));
      const bool complete = f.gcount() == std::streamsize(rgbw.size() * sizeof(float));
      f.close();
      std::error_code ec;
      fs::remove(file, ec);
      if (!complete) {
        error = "the peer's pass file " + file + " is shorter than " +
                std::to_string(cam.width) + "x" + std::to_string(cam.height) + "x4 floats";
        break;
      }
      pass.rgbw = &rgbw;
      on_pass(pass);
      if (o.cancel && o.cancel->load()) {
        child.Send("stop");
        *interrupted = true;
        break;
      }
      child.Send("next");
    } else if (event == "done") {
      done = true;
    }
  }
  const int status = child.Finish();
  if (!error.empty()) return Status::Error("mitsuba3: " + error);
  if (o.cancel && o.cancel->load()) *interrupted = true;
  if (*interrupted) return Status::Ok();
  if (status == kPeerExitInput || status == kPeerExitNoMitsuba || status != 0 || !done)
    return Status::Error("mitsuba3: the peer runner " + script + " ended with status " +
                         std::to_string(status) + " before finishing (see its messages above)");
  return Status::Ok();
}

}  // namespace ptlab
