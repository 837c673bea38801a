#pragma once
// EvdevIo on a real /dev/input/eventN file descriptor (Linux <linux/input.h>).
// What it does that the tests' fake does not: the kernel answers EVIOCGBIT
// in unsigned long words (repacked here into the portable bit order of
// evdev_io.h), reads come in whole input_event records, and a node
// unplugged while open answers read, write and ioctl with ENODEV.

#include <string>
#include <utility>

#include "evdev_io.h"

namespace sculpt::hal::evdev_ff {

class LinuxEvdevIo final : public EvdevIo {
 public:
  LinuxEvdevIo() = default;
  /// Lists and describes nodes under other roots than /dev/input and
  /// /sys/class/input: the tests' fake tree in a temporary directory.
  LinuxEvdevIo(std::string input_dir, std::string sysfs_input_dir)
      : input_dir_(std::move(input_dir)), sysfs_input_dir_(std::move(sysfs_input_dir)) {}
  ~LinuxEvdevIo() override;
  LinuxEvdevIo(const LinuxEvdevIo&) = delete;
  LinuxEvdevIo& operator=(const LinuxEvdevIo&) = delete;

  std::vector<std::string> list_event_nodes() override;
  std::optional<EvdevSysfs> sysfs(const std::string& node) override;
  int open(const std::string& node) override;
  void close() override;
  int get_bits(uint16_t ev_type, std::span<uint8_t> bits) override;
  int get_key_state(std::span<uint8_t> bits) override;
  int get_abs(uint16_t axis, input_absinfo& out) override;
  int get_id(input_id& out) override;
  int get_name(std::string& out) override;
  int upload_effect(ff_effect& effect) override;
  int remove_effect(int16_t id) override;
  long write_bytes(std::span<const uint8_t> bytes) override;
  long read_bytes(std::span<uint8_t> buf) override;
  int poll_readable(int timeout_ms) override;

 private:
  int fd_ = -1;
  std::string input_dir_ = "/dev/input";
  std::string sysfs_input_dir_ = "/sys/class/input";
};

}  // namespace sculpt::hal::evdev_ff
