// A pdf answered by another program: one child process per batch, poll() with a deadline.
#include "tools/chi2/check/pdf_command.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <thread>
#include <vector>

#include "engine/core/parse_number.h"

namespace ptlab {
namespace {

using Clock = std::chrono::steady_clock;

// SIGPIPE ignored while we write to the program: a program that exits early gives EPIPE.
class IgnoreSigpipe {
 public:
  IgnoreSigpipe() {
    struct sigaction ignore {};
    ignore.sa_handler = SIG_IGN;
    sigaction(SIGPIPE, &ignore, &old_);
  }
  ~IgnoreSigpipe() { sigaction(SIGPIPE, &old_, nullptr); }

 private:
  struct sigaction old_ {};
};

std::string Points(const chi2::Point* p, int64_t n, int dims) {
  std::string text;
  text.reserve(size_t(n) * size_t(dims) * 16);
  char line[128];
  for (int64_t i = 0; i < n; ++i) {
    if (dims == 3) {
      std::snprintf(line, sizeof(line), "%.17g %.17g %.17g\n", double(p[i].x), double(p[i].y),
                    double(p[i].z));
    } else {
      std::snprintf(line, sizeof(line), "%.17g %.17g\n", double(p[i].x), double(p[i].y));
    }
    text += line;
  }
  return text;
}

// Parses exactly n densities from the program's output.
chi2::Status ParseDensities(const std::string& who, const std::string& out, int64_t n,
                            double* densities) {
  int64_t count = 0, line = 1;
  size_t i = 0;
  while (i < out.size()) {
    if (out[i] == '\n') ++line;
    if (std::isspace(static_cast<unsigned char>(out[i]))) {
      ++i;
      continue;
    }
    size_t j = i;
    while (j < out.size() && !std::isspace(static_cast<unsigned char>(out[j]))) ++j;
    const std::string_view token(out.data() + i, j - i);
    double v = 0;
    if (!ParseDoubleOrNonFinite(token, &v))
      return chi2::Status::Error(who + " printed " + QuoteForMessage(token) + " on line " +
                                 std::to_string(line) +
                                 " of its output: expected one density (a number) per line");
    // NaN, Inf and 1e400 stay what they are: the test reports non-finite densities.
    if (count < n) densities[count] = v;
    ++count;
    i = j;
  }
  if (count != n)
    return chi2::Status::Error(who + " printed " + std::to_string(count) + " densities for " +
                               std::to_string(n) + " points: expected one per point");
  return chi2::Status::Ok();
}

chi2::Status RunBatch(const std::string& command, int dims, double timeout_seconds,
                      const chi2::Point* p, int64_t n, double* densities) {
  const std::string who = "the pdf program \"" + command + "\"";
  const std::string input = Points(p, n, dims);
  int to_child[2], from_child[2];
  if (pipe2(to_child, O_CLOEXEC) != 0)
    return chi2::Status::Error("pipe: " + std::string(strerror(errno)));
  if (pipe2(from_child, O_CLOEXEC) != 0) {
    close(to_child[0]), close(to_child[1]);
    return chi2::Status::Error("pipe: " + std::string(strerror(errno)));
  }
  IgnoreSigpipe ignore_sigpipe;
  const pid_t pid = fork();
  if (pid < 0) {
    close(to_child[0]), close(to_child[1]), close(from_child[0]), close(from_child[1]);
    return chi2::Status::Error(who + ": fork failed: " + strerror(errno));
  }
  if (pid == 0) {
    setpgid(0, 0);  // its own group, so a timeout kills the shell and what it started
    signal(SIGPIPE, SIG_DFL);
    dup2(to_child[0], 0);
    dup2(from_child[1], 1);
    execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  setpgid(pid, pid);
  close(to_child[0]), close(from_child[1]);
  int in = to_child[1];
  const int out = from_child[0];
  fcntl(in, F_SETFL, O_NONBLOCK);
  fcntl(out, F_SETFL, O_NONBLOCK);
  const Clock::time_point deadline =
      Clock::now() + std::chrono::milliseconds(int64_t(timeout_seconds * 1000.0));
  auto remaining_ms = [&] {
    return int(std::max<int64_t>(
        0, std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count()));
  };
  std::string output;
  size_t written = 0;
  bool timed_out = false, too_much = false;
  // A density per line needs at most ~32 bytes ("%.17g\n" is 25); more is a program that
  // prints forever (or garbage), stopped before its output exhausts memory.
  const size_t max_output = size_t(n) * 64 + 4096;
  for (;;) {
    pollfd fds[2] = {{out, POLLIN, 0}, {in, POLLOUT, 0}};
    const int nfds = in >= 0 ? 2 : 1;
    const int wait = remaining_ms();
    if (wait == 0) {
      timed_out = true;
      break;
    }
    if (poll(fds, nfds, wait) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    if (in >= 0 && (fds[1].revents & (POLLOUT | POLLERR | POLLHUP))) {
      const ssize_t w = write(in, input.data() + written, input.size() - written);
      if (w > 0) written += size_t(w);
      if ((w < 0 && errno != EAGAIN) || written == input.size()) close(in), in = -1;
    }
    if (fds[0].revents & (POLLIN | POLLHUP | POLLERR)) {
      char buf[65536];
      const ssize_t r = read(out, buf, sizeof(buf));
      if (r > 0) {
        if (output.size() + size_t(r) > max_output) {
          too_much = true;
          break;
        }
        output.append(buf, size_t(r));
      } else if (r == 0 || errno != EAGAIN) {
        break;  // end of its output
      }
    }
  }
  if (in >= 0) close(in);
  close(out);
  int status = 0;
  if (too_much) {
    kill(-pid, SIGKILL);
    waitpid(pid, &status, 0);
    return chi2::Status::Error(who + " printed more than " + std::to_string(max_output) +
                               " bytes for " + std::to_string(n) +
                               " points (killed); expected one density per line");
  }
  while (!timed_out) {
    const pid_t done = waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (remaining_ms() == 0) {
      timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (timed_out) {
    kill(-pid, SIGKILL);
    waitpid(pid, &status, 0);
    return chi2::Status::Error(who + " did not answer " + std::to_string(n) + " points within " +
                               std::to_string(int(timeout_seconds)) +
                               " s (killed; --pdf-timeout sets the limit)");
  }
  if (WIFSIGNALED(status))
    return chi2::Status::Error(who + " was killed by signal " + std::to_string(WTERMSIG(status)) +
                               " (" + strsignal(WTERMSIG(status)) + ")");
  if (WIFEXITED(status) && WEXITSTATUS(status) != 0)
    return chi2::Status::Error(who + " exited with status " + std::to_string(WEXITSTATUS(status)) +
                               (WEXITSTATUS(status) == 127 ? " (command not found?)" : ""));
  if (written != input.size())
    return chi2::Status::Error(who + " exited before reading all " + std::to_string(n) +
                               " points from its stdin");
  return ParseDensities(who, output, n, densities);
}

}  // namespace

chi2::PdfFn PdfCommand(const std::string& command, const chi2::Domain& domain,
                       double timeout_seconds) {
  const int dims = domain.dims();
  return [command, dims, timeout_seconds](const chi2::Point* p, int64_t n, double* densities) {
    return RunBatch(command, dims, timeout_seconds, p, n, densities);
  };
}

}  // namespace ptlab
