// The bit helpers of the evdev edge.

#include "evdev_io.h"

#include <cerrno>
#include <charconv>
#include <cstring>
#include <sstream>

namespace sculpt::hal::evdev_ff {

std::string evdev_open_error(const std::string& node, int minus_errno) {
  const int e = -minus_errno;
  if (e == EACCES || e == EPERM) {
    // Event nodes are root:input 0660 (udev's 50-udev-default.rules), and
    // logind grants the seat's user an ACL only on nodes tagged uaccess.
    return node +
           ": permission denied; join the input group (sudo usermod -aG input $USER, then log "
           "in again) or add a udev rule giving this device TAG+=\"uaccess\"";
  }
  if (e == ENOENT || e == ENODEV || e == ENXIO) return node + ": no such device (unplugged?)";
  return node + ": cannot open: " + std::strerror(e);
}

bool evdev_bit(std::span<const uint8_t> bits, size_t i) {
  return i / 8 < bits.size() && ((bits[i / 8] >> (i % 8)) & 1u) != 0;
}

bool sysfs_bitmap_bit(const std::string& bitmap, size_t i, size_t word_bits) {
  // The kernel's input_print_bitmap() writes the words from the highest to
  // word 0, each as %lx, separated by spaces (leading zero words dropped):
  // so the last word holds bits 0..word_bits-1.
  std::vector<std::string> words;
  std::istringstream in(bitmap);
  for (std::string w; in >> w;)
    words.push_back(w);
  const size_t word = i / word_bits;
  if (word >= words.size() || word_bits > 64) return false;
  const std::string& text = words[words.size() - 1 - word];
  uint64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value, 16);
  if (ec != std::errc() || end != text.data() + text.size()) return false;
  return ((value >> (i % word_bits)) & 1u) != 0;
}

}  // namespace sculpt::hal::evdev_ff
