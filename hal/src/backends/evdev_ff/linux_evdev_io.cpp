// LinuxEvdevIo: the system calls behind EvdevIo.

#include "linux_evdev_io.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

namespace sculpt::hal::evdev_ff {
namespace {

constexpr size_t kLongBits = CHAR_BIT * sizeof(unsigned long);

int minus_errno() {
  return -errno;
}

// An ioctl retried when a signal interrupts it.
template <class Arg>
int checked_ioctl(int fd, unsigned long request, Arg arg) {
  int r;
  do {
    r = ::ioctl(fd, request, arg);
  } while (r < 0 && errno == EINTR);
  return r < 0 ? minus_errno() : r;
}

// The kernel copies EVIOCGBIT and EVIOCGKEY out as unsigned long words
// (bits_to_user in drivers/input/evdev.c), so on a big-endian machine the
// bytes of a word are not in bit order: read words, then repack.
// request(len) is the ioctl for a buffer of len bytes.
template <class Request>
int get_bitmap(int fd, std::span<uint8_t> bits, Request request) {
  std::vector<unsigned long> words((bits.size() * CHAR_BIT + kLongBits - 1) / kLongBits, 0ul);
  const int r = checked_ioctl(fd, request(words.size() * sizeof(unsigned long)), words.data());
  if (r < 0) return r;
  std::fill(bits.begin(), bits.end(), uint8_t{0});
  for (size_t i = 0; i < bits.size() * CHAR_BIT; ++i) {
    if ((words[i / kLongBits] >> (i % kLongBits)) & 1ul)
      bits[i / CHAR_BIT] = static_cast<uint8_t>(bits[i / CHAR_BIT] | (1u << (i % CHAR_BIT)));
  }
  return 0;
}

std::string node_name(const std::string& node) {
  return std::filesystem::path(node).filename().string();
}

// "event12" -> 12; -1 for any other name.
long event_number(const std::string& name) {
  if (name.rfind("event", 0) != 0 || name.size() == 5) return -1;
  long n = 0;
  const char* begin = name.data() + 5;
  const char* end = name.data() + name.size();
  const auto [at, ec] = std::from_chars(begin, end, n);
  return ec == std::errc() && at == end ? n : -1;
}

std::optional<std::string> read_line(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  if (!in || !std::getline(in, line)) return std::nullopt;
  return line;
}

std::optional<uint16_t> read_hex16(const std::filesystem::path& path) {
  const auto line = read_line(path);
  if (!line) return std::nullopt;
  unsigned value = 0;
  const auto [at, ec] = std::from_chars(line->data(), line->data() + line->size(), value, 16);
  if (ec != std::errc() || value > 0xffff) return std::nullopt;
  return static_cast<uint16_t>(value);
}

// A path component shaped like a USB port path: "1-4" or "1-4.2".
bool is_usb_port(const std::string& s) {
  const size_t dash = s.find('-');
  if (dash == std::string::npos || dash == 0 || dash + 1 == s.size()) return false;
  for (size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (i == dash) continue;
    if (!std::isdigit(static_cast<unsigned char>(c)) && !(c == '.' && i > dash + 1)) return false;
  }
  return true;
}

}  // namespace

LinuxEvdevIo::~LinuxEvdevIo() {
  close();
}

std::vector<std::string> LinuxEvdevIo::list_event_nodes() {
  std::vector<std::pair<long, std::string>> found;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(input_dir_, ec)) {
    const std::string name = entry.path().filename().string();
    if (const long n = event_number(name); n >= 0) found.emplace_back(n, entry.path().string());
  }
  std::sort(found.begin(), found.end());
  std::vector<std::string> nodes;
  for (auto& [n, path] : found)
    nodes.push_back(std::move(path));
  return nodes;
}

std::optional<EvdevSysfs> LinuxEvdevIo::sysfs(const std::string& node) {
  const std::filesystem::path dir = std::filesystem::path(sysfs_input_dir_) / node_name(node);
  const std::filesystem::path device = dir / "device";
  auto name = read_line(device / "name");
  auto vendor = read_hex16(device / "id" / "vendor");
  auto product = read_hex16(device / "id" / "product");
  if (!name || !vendor || !product) return std::nullopt;
  EvdevSysfs s;
  s.name = std::move(*name);
  s.vendor_id = *vendor;
  s.product_id = *product;
  s.ff_bitmap = read_line(device / "capabilities" / "ff").value_or("");
  s.ev_bitmap = read_line(device / "capabilities" / "ev").value_or("");
  s.abs_bitmap = read_line(device / "capabilities" / "abs").value_or("");
  s.rel_bitmap = read_line(device / "capabilities" / "rel").value_or("");
  s.key_bitmap = read_line(device / "capabilities" / "key").value_or("");
  s.properties_bitmap = read_line(device / "properties").value_or("");
  s.uniq = read_line(device / "uniq").value_or("");
  std::error_code ec;
  // .../usb1/1-4/1-4.2/1-4.2:1.0/0003:.../input/input17/event5: the USB
  // device is the last component shaped like "1-4.2".
  const auto real = std::filesystem::canonical(dir, ec);
  if (!ec) {
    for (const auto& part : real) {
      if (is_usb_port(part.string())) s.usb_location = part.string();
    }
  }
  return s;
}

int LinuxEvdevIo::open(const std::string& node) {
  close();
  // Read-write: force feedback is driven by write() and EVIOCSFF, which
  // evdev refuses on a read-only descriptor. Non-blocking: read() drains
  // what is pending and never waits for a stick that does not move.
  const int fd = ::open(node.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return minus_errno();
  fd_ = fd;
  return 0;
}

void LinuxEvdevIo::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

int LinuxEvdevIo::get_bits(uint16_t ev_type, std::span<uint8_t> bits) {
  return get_bitmap(fd_, bits, [ev_type](size_t len) { return EVIOCGBIT(ev_type, len); });
}

int LinuxEvdevIo::get_key_state(std::span<uint8_t> bits) {
  return get_bitmap(fd_, bits, [](size_t len) { return EVIOCGKEY(len); });
}

int LinuxEvdevIo::get_abs(uint16_t axis, input_absinfo& out) {
  const int r = checked_ioctl(fd_, EVIOCGABS(axis), &out);
  return r < 0 ? r : 0;
}

int LinuxEvdevIo::get_id(input_id& out) {
  const int r = checked_ioctl(fd_, EVIOCGID, &out);
  return r < 0 ? r : 0;
}

int LinuxEvdevIo::get_name(std::string& out) {
  char buf[256] = {};
  const int r = checked_ioctl(fd_, EVIOCGNAME(sizeof buf - 1), buf);
  if (r < 0) return r;
  out.assign(buf, strnlen(buf, sizeof buf - 1));
  return 0;
}

int LinuxEvdevIo::upload_effect(ff_effect& effect) {
  const int r = checked_ioctl(fd_, EVIOCSFF, &effect);
  return r < 0 ? r : 0;
}

int LinuxEvdevIo::remove_effect(int16_t id) {
  // EVIOCRMFF takes the id by value, not a pointer (ff.rst).
  const int r = checked_ioctl(fd_, EVIOCRMFF, static_cast<long>(id));
  return r < 0 ? r : 0;
}

long LinuxEvdevIo::write_bytes(std::span<const uint8_t> bytes) {
  ssize_t n;
  do {
    n = ::write(fd_, bytes.data(), bytes.size());
  } while (n < 0 && errno == EINTR);
  return n < 0 ? minus_errno() : static_cast<long>(n);
}

long LinuxEvdevIo::read_bytes(std::span<uint8_t> buf) {
  ssize_t n;
  do {
    n = ::read(fd_, buf.data(), buf.size());
  } while (n < 0 && errno == EINTR);
  return n < 0 ? minus_errno() : static_cast<long>(n);
}

int LinuxEvdevIo::poll_readable(int timeout_ms) {
  pollfd p{fd_, POLLIN, 0};
  int r;
  do {
    r = ::poll(&p, 1, timeout_ms);
  } while (r < 0 && errno == EINTR);
  if (r < 0) return minus_errno();
  // evdev_poll() answers POLLHUP | POLLERR once the device is gone.
  if (r > 0 && (p.revents & (POLLHUP | POLLERR)) != 0) return -ENODEV;
  return r > 0 ? 1 : 0;
}

}  // namespace sculpt::hal::evdev_ff
