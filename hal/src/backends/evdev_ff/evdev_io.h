#pragma once
// The byte and ioctl edge of a Linux evdev node (/dev/input/eventN) as the
// force-feedback backend uses it: open and close, the EVIOCG* queries, the
// effect ioctls EVIOCSFF and EVIOCRMFF, write() and read() of struct
// input_event, poll(). LinuxEvdevIo (linux_evdev_io.h) drives a real node;
// the tests and the fuzz target drive a scripted fake
// (tests/hal/backends/evdev_ff/fake_evdev_io.h), the only way to exercise
// the backend in CI, which has neither a force-feedback device nor
// /dev/uinput.
//
// Errors are returned as -errno (0 or a count on success), so a caller can
// tell ENODEV (the device was unplugged) and EACCES (no permission) from the
// rest, and EAGAIN (nothing to read) from a failure.
//
// Thread safety: none; one thread uses an EvdevIo at a time.

#include <linux/input.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace sculpt::hal::evdev_ff {

/// What sysfs (/sys/class/input/eventN/device/) says about a node, readable
/// without opening it: how a node this user may not open is still listed.
struct EvdevSysfs {
  std::string name;
  uint16_t vendor_id = 0;
  uint16_t product_id = 0;
  /// capabilities/ff as the kernel prints it: hexadecimal words of the
  /// kernel's unsigned long, most significant first ("107030000 0").
  std::string ff_bitmap;
  /// The USB port path ("1-4.2"), empty when not on USB.
  std::string usb_location;
  /// capabilities/ev, abs, rel, key and properties, printed like ff_bitmap
  /// (the 6-axis input backend's filter; empty when sysfs lacks them).
  std::string ev_bitmap;
  std::string abs_bitmap;
  std::string rel_bitmap;
  std::string key_bitmap;
  std::string properties_bitmap;
  /// uniq: the serial number or Bluetooth address, as hidraw's HID_UNIQ.
  std::string uniq;
};

class EvdevIo {
 public:
  virtual ~EvdevIo() = default;

  /// The event nodes present, "/dev/input/event0" ..., in numeric order.
  virtual std::vector<std::string> list_event_nodes() = 0;
  /// nullopt when sysfs does not describe `node`.
  virtual std::optional<EvdevSysfs> sysfs(const std::string& node) = 0;

  /// Opens `node` read-write and non-blocking, closing any node open before.
  /// 0 or -errno (-EACCES: this user may not open it).
  virtual int open(const std::string& node) = 0;
  /// Closes the node; effects uploaded through it die with it (ff.rst:
  /// "Effects are file descriptor specific").
  virtual void close() = 0;

  /// EVIOCGBIT(ev_type): the codes the device declares for an event type
  /// (ev_type 0: the event types). Bit i is bits[i / 8] >> (i % 8), whatever
  /// the machine's word size and byte order. 0 or -errno.
  virtual int get_bits(uint16_t ev_type, std::span<uint8_t> bits) = 0;
  /// EVIOCGKEY: the keys held now, in get_bits()'s bit order. 0 or -errno.
  virtual int get_key_state(std::span<uint8_t> bits) = 0;
  /// EVIOCGABS(axis): the axis's range and its current value. 0 or -errno.
  virtual int get_abs(uint16_t axis, input_absinfo& out) = 0;
  /// EVIOCGID. 0 or -errno.
  virtual int get_id(input_id& out) = 0;
  /// EVIOCGNAME. 0 or -errno.
  virtual int get_name(std::string& out) = 0;

  /// EVIOCSFF: uploads an effect (effect.id -1: a new one, whose id the
  /// kernel writes back) or updates the effect with that id in place. 0 or -errno.
  virtual int upload_effect(ff_effect& effect) = 0;
  /// EVIOCRMFF: removes (and so stops) an effect. 0 or -errno.
  virtual int remove_effect(int16_t id) = 0;

  /// write(): bytes written or -errno. The device takes whole input_event
  /// records (EV_FF play/stop, FF_GAIN, FF_AUTOCENTER).
  virtual long write_bytes(std::span<const uint8_t> bytes) = 0;
  /// read() without waiting: bytes read (whole input_event records from a
  /// real node), or -errno; -EAGAIN when nothing is pending.
  virtual long read_bytes(std::span<uint8_t> buf) = 0;
  /// poll() for input: 1 readable, 0 timed out, or -errno (-ENODEV once the
  /// node reports POLLHUP or POLLERR).
  virtual int poll_readable(int timeout_ms) = 0;
};

/// Why `node` would not open, for the user: for EACCES/EPERM how to get
/// access (the input group, or a udev rule with TAG+="uaccess").
std::string evdev_open_error(const std::string& node, int minus_errno);

/// bits[i / 8] >> (i % 8), false beyond the span.
bool evdev_bit(std::span<const uint8_t> bits, size_t i);

/// Whether a capabilities bitmap as sysfs prints it (EvdevSysfs::ff_bitmap)
/// has bit `i`, for words of `word_bits` bits (the kernel's unsigned long).
bool sysfs_bitmap_bit(const std::string& bitmap, size_t i,
                      size_t word_bits = 8 * sizeof(unsigned long));

}  // namespace sculpt::hal::evdev_ff
