#include "is_graphs/common/run_process.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace is_graphs {
namespace {

void CloseIfOpen(int* fd) {
  if (*fd >= 0) close(*fd);
  *fd = -1;
}

// Reads what is available on fd into out; false at end of file or on error.
bool Drain(int fd, std::string* out) {
  char buffer[4096];
  const ssize_t n = read(fd, buffer, sizeof(buffer));
  if (n > 0) {
    out->append(buffer, static_cast<size_t>(n));
    return true;
  }
  return n < 0 && errno == EINTR;
}

}  // namespace

ProcessOutput RunProcess(const std::vector<std::string>& argv) {
  ProcessOutput result;
  if (argv.empty()) {
    result.error = "no program given";
    return result;
  }
  int out[2], err[2], status[2];  // status: the child's errno when exec fails
  if (pipe2(out, O_CLOEXEC) != 0 || pipe2(err, O_CLOEXEC) != 0 || pipe2(status, O_CLOEXEC) != 0) {
    result.error = std::string("pipe: ") + std::strerror(errno);
    return result;
  }
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);

  const pid_t pid = fork();
  if (pid < 0) {
    result.error = std::string("fork: ") + std::strerror(errno);
    for (int fd : {out[0], out[1], err[0], err[1], status[0], status[1]}) close(fd);
    return result;
  }
  if (pid == 0) {  // child: only async-signal-safe calls from here on
    const int null_fd = open("/dev/null", O_RDONLY);
    if (null_fd >= 0) dup2(null_fd, STDIN_FILENO);
    dup2(out[1], STDOUT_FILENO);
    dup2(err[1], STDERR_FILENO);
    execvp(args[0], args.data());
    const int exec_errno = errno;
    ssize_t ignored = write(status[1], &exec_errno, sizeof(exec_errno));
    (void)ignored;
    _exit(127);
  }

  close(out[1]);
  close(err[1]);
  close(status[1]);
  int exec_errno = 0;
  ssize_t n;
  do {
    n = read(status[0], &exec_errno, sizeof(exec_errno));
  } while (n < 0 && errno == EINTR);
  close(status[0]);

  int fds[2] = {out[0], err[0]};
  std::string* texts[2] = {&result.stdout_text, &result.stderr_text};
  while (fds[0] >= 0 || fds[1] >= 0) {
    pollfd polled[2] = {{fds[0], POLLIN, 0}, {fds[1], POLLIN, 0}};
    if (poll(polled, 2, -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    for (int i = 0; i < 2; ++i) {
      if (fds[i] >= 0 && polled[i].revents != 0 && !Drain(fds[i], texts[i])) CloseIfOpen(&fds[i]);
    }
  }
  CloseIfOpen(&fds[0]);
  CloseIfOpen(&fds[1]);

  int wait_status = 0;
  while (waitpid(pid, &wait_status, 0) < 0 && errno == EINTR) {
  }
  if (n == static_cast<ssize_t>(sizeof(exec_errno))) {
    result.error = "cannot run " + argv[0] + ": " + std::strerror(exec_errno);
    return result;
  }
  result.started = true;
  if (WIFEXITED(wait_status)) {
    result.exit_code = WEXITSTATUS(wait_status);
  } else if (WIFSIGNALED(wait_status)) {
    result.exit_code = 128 + WTERMSIG(wait_status);
  }
  return result;
}

}  // namespace is_graphs
