#include "sculpt/base/atomic_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "sculpt/base/temp_files.h"

namespace sculpt {

AtomicFileWriter::AtomicFileWriter(std::filesystem::path target) : target_(std::move(target)) {
  // mkstemp gives a unique name in the same folder, so rename() is atomic
  // (same file system) and two writers never share a temporary.
  std::string pattern = target_.string() + ".tmp-XXXXXX";
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
