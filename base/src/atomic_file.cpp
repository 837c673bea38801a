#include "sculpt/base/atomic_file.h"

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "sculpt/base/temp_files.h"

namespace sculpt {

namespace {

// A temporary's name: TARGET.tmp-PID-XXXXXX. The writer's process id lets a
// later writer of the same target tell a temporary left by a process that
// was killed (SIGKILL, a power cut: no handler runs) from one still being
// written, and remove the former: a killed export of a big volume must not
// leave gigabytes beside the target for ever.
std::string temp_prefix(const std::filesystem::path& target) {
  return target.filename().string() + ".tmp-";
}

bool process_alive(pid_t pid) {
  return ::kill(pid, 0) == 0 || errno == EPERM;
}

void remove_stale_temporaries(const std::filesystem::path& target) {
  const std::string prefix = temp_prefix(target);
  std::filesystem::path folder = target.parent_path();
  if (folder.empty()) folder = ".";
  std::error_code error;
  for (std::filesystem::directory_iterator it(folder, error), end; !error && it != end;
       it.increment(error)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= prefix.size() + 7 || name.compare(0, prefix.size(), prefix) != 0) continue;
    // PID-XXXXXX: digits, a dash, mkstemp's six characters.
    const std::string rest = name.substr(prefix.size());
    const size_t dash = rest.find('-');
    if (dash == 0 || dash == std::string::npos || rest.size() - dash != 7) continue;
    if (rest.find_first_not_of("0123456789") != dash) continue;
    const long pid = std::strtol(rest.c_str(), nullptr, 10);
    if (pid <= 0 || pid == ::getpid() || process_alive(static_cast<pid_t>(pid))) continue;
    std::error_code ignored;
    std::filesystem::remove(it->path(), ignored);
  }
}

}  // namespace

AtomicFileWriter::AtomicFileWriter(std::filesystem::path target) : target_(std::move(target)) {
  remove_stale_temporaries(target_);
  // mkstemp gives a unique name in the same folder, so rename() is atomic
  // (same file system) and two writers never share a temporary.
  std::string pattern = target_.string() + ".tmp-" + std::to_string(::getpid()) + "-XXXXXX";
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  const int fd = ::mkstemp(name.data());
  if (fd < 0) {
    error_ = std::string("cannot create file: ") + std::strerror(errno);
    return;
  }
  temp_ = name.data();
  temp_slot_ = remember_temp_file(temp_.string());
  // mkstemp creates 0600; the renamed file must get the mode any new file
  // gets (0666 less the umask), or other programs and users cannot read it.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  file_ = ::fdopen(fd, "wb");
  if (file_ == nullptr) {
    error_ = std::string("cannot open file: ") + std::strerror(errno);
    ::close(fd);
    std::filesystem::remove(temp_);
  }
}

AtomicFileWriter::~AtomicFileWriter() {
  if (file_ != nullptr) std::fclose(file_);
  if (!committed_ && !temp_.empty()) {
    std::error_code ignored;
    std::filesystem::remove(temp_, ignored);
  }
  forget_temp_file(temp_slot_);
}

void AtomicFileWriter::write(const void* data, size_t size) {
  if (!ok() || size == 0) return;
  if (std::fwrite(data, 1, size, file_) != size) {
    error_ = std::string("write failed: ") + std::strerror(errno);
  }
}

Status AtomicFileWriter::commit() {
  if (!ok()) return error();
  if (std::fflush(file_) != 0 || ::fsync(::fileno(file_)) != 0) {
    error_ = std::string("write failed: ") + std::strerror(errno);
    return error();
  }
  std::fclose(file_);
  file_ = nullptr;
  std::error_code ec;
  std::filesystem::rename(temp_, target_, ec);
  if (ec) {
    error_ = "cannot rename temporary file into place: " + ec.message();
    return error();
  }
  committed_ = true;
  forget_temp_file(temp_slot_);
  temp_slot_ = -1;
  return {};
}

}  // namespace sculpt
