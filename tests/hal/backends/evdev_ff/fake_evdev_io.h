#pragma once
// A scripted fake of the evdev edge (EvdevIo) for the tests and the fuzz
// target. CI has no force-feedback device and no /dev/uinput (a uinput
// device with EV_FF would also need a process answering the kernel's
// upload requests), so this fake is the only way the backend runs there.
//
// FakeEvdevSystem is the test's: a directory of fake nodes, the log of
// every call with the bytes that went to the device (the ff_effect of an
// EVIOCSFF, the input_event of a write, the id of an EVIOCRMFF) and the
// ioctl request a real node would have received, and the failures to
// answer with. FakeEvdevIo is the EvdevIo the device owns; it forwards to
// the system, so the log outlives the device (the destructor's calls are
// in it).

#include <linux/input.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstring>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "backends/evdev_ff/evdev_io.h"

namespace sculpt::hal::evdev_ff::testing {

enum class Op {
  kOpen,
  kClose,
  kGetBits,
  kGetKeyState,
  kGetAbs,
  kGetId,
  kGetName,
  kUpload,
  kRemove,
  kWrite,
  kRead,
  kPoll
};

struct IoCall {
  Op op;
  /// The ioctl request a real node gets (EVIOCSFF, EVIOCGABS(ABS_X), ...); 0 for the rest.
  unsigned long request = 0;
  std::string node;            ///< for kOpen
  std::vector<uint8_t> bytes;  ///< what went to the device
  long result = 0;
};

/// One fake /dev/input/eventN.
struct FakeEvdevNode {
  int open_error = 0;  ///< -errno open() answers (-EACCES: not this user's)
  std::optional<EvdevSysfs> sysfs;
  std::set<uint16_t> ev_types;
  std::set<uint16_t> ff;
  std::set<uint16_t> abs;
  std::set<uint16_t> rel;
  std::map<uint16_t, input_absinfo> absinfo;
  std::set<uint16_t> keys;
  std::set<uint16_t> held;  ///< what EVIOCGKEY answers
  input_id id{};
  std::string name;
  /// Each entry is what one read() returns (split if the buffer is smaller).
  std::deque<std::vector<uint8_t>> reads;
};

inline std::vector<uint8_t> bytes_of(const void* p, size_t n) {
  const auto* b = static_cast<const uint8_t*>(p);
  return std::vector<uint8_t>(b, b + n);
}

inline input_event make_event(uint16_t type, uint16_t code, int32_t value) {
  input_event ev{};
  ev.type = type;
  ev.code = code;
  ev.value = value;
  return ev;
}

/// The capabilities bitmap as sysfs prints it for these codes, in words of
/// this machine's unsigned long (input_print_bitmap).
inline std::string sysfs_bitmap(const std::set<uint16_t>& codes) {
  constexpr size_t kBits = CHAR_BIT * sizeof(unsigned long);
  std::vector<unsigned long> words(1, 0ul);
  for (uint16_t c : codes) {
    if (c / kBits >= words.size()) words.resize(c / kBits + 1, 0ul);
    words[c / kBits] |= 1ul << (c % kBits);
  }
  while (words.size() > 1 && words.back() == 0)
    words.pop_back();
  std::ostringstream out;
  for (size_t i = words.size(); i-- > 0;)
    out << std::hex << words[i] << (i > 0 ? " " : "");
  return out.str();
}

class FakeEvdevSystem {
 public:
  std::map<std::string, FakeEvdevNode> nodes;
  std::vector<IoCall> calls;
  /// Every call on an open node answers -ENODEV (the device was unplugged).
  bool gone = false;
  /// -errno the next calls of an op answer, one each, before any other answer.
  std::map<Op, std::deque<long>> failures;
  int16_t next_effect_id = 0;
  std::set<int16_t> effects;  ///< uploaded and not removed

  FakeEvdevNode& node(const std::string& path) { return nodes.at(path); }

  /// Queues events as what one read() returns.
  void queue(const std::string& path, std::initializer_list<input_event> events) {
    std::vector<uint8_t> chunk;
    for (const input_event& ev : events) {
      const auto b = bytes_of(&ev, sizeof ev);
      chunk.insert(chunk.end(), b.begin(), b.end());
    }
    node(path).reads.push_back(std::move(chunk));
  }

  std::vector<IoCall> calls_of(Op op) const {
    std::vector<IoCall> out;
    for (const IoCall& c : calls) {
      if (c.op == op) out.push_back(c);
    }
    return out;
  }
  /// The effects sent with EVIOCSFF, as sent (before the kernel's id).
  std::vector<ff_effect> uploads() const {
    std::vector<ff_effect> out;
    for (const IoCall& c : calls_of(Op::kUpload)) {
      ff_effect e{};
      std::memcpy(&e, c.bytes.data(), sizeof e);
      out.push_back(e);
    }
    return out;
  }
  /// The events written.
  std::vector<input_event> writes() const {
    std::vector<input_event> out;
    for (const IoCall& c : calls_of(Op::kWrite)) {
      input_event ev{};
      std::memcpy(&ev, c.bytes.data(), std::min(c.bytes.size(), sizeof ev));
      out.push_back(ev);
    }
    return out;
  }

  // Answers the next queued failure of `op`, if any.
  std::optional<long> take_failure(Op op) {
    auto it = failures.find(op);
    if (it == failures.end() || it->second.empty()) return std::nullopt;
    const long r = it->second.front();
    it->second.pop_front();
    return r;
  }
};

class FakeEvdevIo final : public EvdevIo {
 public:
  explicit FakeEvdevIo(FakeEvdevSystem& system) : sys_(system) {}

  std::vector<std::string> list_event_nodes() override {
    std::vector<std::string> out;
    for (const auto& [path, node] : sys_.nodes)
      out.push_back(path);
    return out;
  }
  std::optional<EvdevSysfs> sysfs(const std::string& path) override {
    const auto it = sys_.nodes.find(path);
    return it == sys_.nodes.end() ? std::nullopt : it->second.sysfs;
  }
  int open(const std::string& path) override {
    close();
    long r = 0;
    const auto it = sys_.nodes.find(path);
    if (auto f = sys_.take_failure(Op::kOpen)) {
      r = *f;
    } else if (it == sys_.nodes.end() || sys_.gone) {
      r = -ENOENT;
    } else {
      r = it->second.open_error;
    }
    sys_.calls.push_back({Op::kOpen, 0, path, {}, r});
    if (r == 0) open_ = path;
    return static_cast<int>(r);
  }
  void close() override {
    if (open_.empty()) return;
    sys_.calls.push_back({Op::kClose, 0, open_, {}, 0});
    open_.clear();
  }
  int get_bits(uint16_t ev_type, std::span<uint8_t> bits) override {
    const long r = answer(Op::kGetBits);
    record(Op::kGetBits, EVIOCGBIT(ev_type, bits.size()), {}, r);
    if (r < 0) return static_cast<int>(r);
    const FakeEvdevNode& n = node();
    const std::set<uint16_t>* codes = ev_type == 0        ? &n.ev_types
                                      : ev_type == EV_FF  ? &n.ff
                                      : ev_type == EV_ABS ? &n.abs
                                      : ev_type == EV_REL ? &n.rel
                                      : ev_type == EV_KEY ? &n.keys
                                                          : nullptr;
    fill(bits, codes);
    return 0;
  }
  int get_key_state(std::span<uint8_t> bits) override {
    const long r = answer(Op::kGetKeyState);
    record(Op::kGetKeyState, EVIOCGKEY(bits.size()), {}, r);
    if (r < 0) return static_cast<int>(r);
    fill(bits, &node().held);
    return 0;
  }
  int get_abs(uint16_t axis, input_absinfo& out) override {
    long r = answer(Op::kGetAbs);
    const auto it = r == 0 ? node().absinfo.find(axis) : node().absinfo.end();
    if (r == 0 && it == node().absinfo.end()) r = -EINVAL;
    record(Op::kGetAbs, EVIOCGABS(axis), {}, r);
    if (r < 0) return static_cast<int>(r);
    out = it->second;
    return 0;
  }
  int get_id(input_id& out) override {
    const long r = answer(Op::kGetId);
    record(Op::kGetId, EVIOCGID, {}, r);
    if (r == 0) out = node().id;
    return static_cast<int>(r);
  }
  int get_name(std::string& out) override {
    const long r = answer(Op::kGetName);
    record(Op::kGetName, EVIOCGNAME(256), {}, r);
    if (r == 0) out = node().name;
    return static_cast<int>(r);
  }
  int upload_effect(ff_effect& effect) override {
    long r = answer(Op::kUpload);
    if (r == 0 && effect.id != -1 && sys_.effects.count(effect.id) == 0) r = -EINVAL;
    record(Op::kUpload, EVIOCSFF, bytes_of(&effect, sizeof effect), r);
    if (r < 0) return static_cast<int>(r);
    if (effect.id == -1) {
      // ff.rst: the kernel writes the new effect's id back.
      effect.id = sys_.next_effect_id++;
      sys_.effects.insert(effect.id);
    }
    return 0;
  }
  int remove_effect(int16_t id) override {
    long r = answer(Op::kRemove);
    if (r == 0 && sys_.effects.erase(id) == 0) r = -EINVAL;
    const int as_int = id;
    record(Op::kRemove, EVIOCRMFF, bytes_of(&as_int, sizeof as_int), r);
    return static_cast<int>(r);
  }
  long write_bytes(std::span<const uint8_t> bytes) override {
    const long r = answer(Op::kWrite);
    record(Op::kWrite, 0, std::vector<uint8_t>(bytes.begin(), bytes.end()), r);
    return r < 0 ? r : static_cast<long>(bytes.size());
  }
  long read_bytes(std::span<uint8_t> buf) override {
    long r = answer(Op::kRead);
    if (r == 0) {
      auto& reads = node().reads;
      if (reads.empty()) {
        r = -EAGAIN;
      } else {
        std::vector<uint8_t>& chunk = reads.front();
        const size_t n = std::min(buf.size(), chunk.size());
        std::copy_n(chunk.begin(), n, buf.begin());
        chunk.erase(chunk.begin(), chunk.begin() + static_cast<ptrdiff_t>(n));
        if (chunk.empty()) reads.pop_front();
        r = static_cast<long>(n);
      }
    }
    record(Op::kRead, 0, {}, r);
    return r;
  }
  int poll_readable(int) override {
    long r = answer(Op::kPoll);
    if (r == 0) r = node().reads.empty() ? 0 : 1;
    record(Op::kPoll, 0, {}, r);
    return static_cast<int>(r);
  }

 private:
  FakeEvdevNode& node() { return sys_.nodes.at(open_); }
  // What a call on the open node answers before its own work: a queued
  // failure, -ENODEV when unplugged, -EBADF when nothing is open.
  long answer(Op op) {
    if (auto f = sys_.take_failure(op)) return *f;
    if (sys_.gone) return -ENODEV;
    if (open_.empty()) return -EBADF;
    return 0;
  }
  void record(Op op, unsigned long request, std::vector<uint8_t> bytes, long result) {
    sys_.calls.push_back({op, request, open_, std::move(bytes), result});
  }
  static void fill(std::span<uint8_t> bits, const std::set<uint16_t>* codes) {
    std::fill(bits.begin(), bits.end(), uint8_t{0});
    if (codes == nullptr) return;
    for (uint16_t c : *codes) {
      if (c / 8u < bits.size())
        bits[c / 8u] = static_cast<uint8_t>(bits[c / 8u] | (1u << (c % 8u)));
    }
  }

  FakeEvdevSystem& sys_;
  std::string open_;
};

}  // namespace sculpt::hal::evdev_ff::testing
