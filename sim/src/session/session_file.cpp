#include "sculpt/sim/session/session_file.h"

#include <fcntl.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "sculpt/base/atomic_file.h"
#include "sculpt/sim/session/command_limits.h"

namespace sculpt::sim {
namespace {

constexpr size_t kRecordHeadBytes = 12;

enum RecordKindByte : uint8_t {
  kReportRecord = 1,
  kAxisRecord = 2,
  kButtonRecord = 3,
  kSyncRecord = 4,
  kRemovedRecord = 5,
  kHapticStartRecord = 6,
  kHapticPatchRecord = 7,
  kHapticTickRecord = 8,
  kCommandRecord = 16,
  // A kToolVoxels command: its voxels split over records of at most
  // kToolChunkBytes (a record's payload length is 16 bits), all at its time.
  kToolChunkRecord = 17,
};
constexpr uint8_t kToolChunkFirst = 1;
constexpr uint8_t kToolChunkLast = 2;
constexpr size_t kToolChunkBytes = 60000;
// The tool's head in the first chunk: dims (3 x u16), pivot (3 x f32), hardness (f32).
constexpr size_t kToolHeadBytes = 22;

uint32_t crc(std::span<const uint8_t> bytes) {
  return static_cast<uint32_t>(crc32(0, bytes.data(), static_cast<uInt>(bytes.size())));
}

// Little-endian encoding into a byte vector.
class Writer {
 public:
  explicit Writer(std::vector<uint8_t>& out) : out_(out) {}
  template <class T>
  void num(T v) {
    uint8_t b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));  // the project only targets little-endian hosts
    out_.insert(out_.end(), b, b + sizeof(T));
  }
  void bytes(std::span<const uint8_t> b) { out_.insert(out_.end(), b.begin(), b.end()); }
  void blob(std::span<const uint8_t> b) {
    num(static_cast<uint32_t>(b.size()));
    bytes(b);
  }
  void str(const std::string& s) { blob({reinterpret_cast<const uint8_t*>(s.data()), s.size()}); }

 private:
  std::vector<uint8_t>& out_;
};

// Bounds-checked little-endian decoding: every read says whether it fitted.
class Reader {
 public:
  explicit Reader(std::span<const uint8_t> in) : in_(in) {}
  template <class T>
  bool num(T& v) {
    if (left() < sizeof(T)) return false;
    std::memcpy(&v, in_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return true;
  }
  bool bytes(size_t n, std::span<const uint8_t>& out) {
    if (left() < n) return false;
    out = in_.subspan(at_, n);
    at_ += n;
    return true;
  }
  bool blob(std::vector<uint8_t>& out, uint32_t max) {
    uint32_t n;
    std::span<const uint8_t> b;
    if (!num(n) || n > max || !bytes(n, b)) return false;
    out.assign(b.begin(), b.end());
    return true;
  }
  bool str(std::string& out, uint32_t max) {
    std::vector<uint8_t> b;
    if (!blob(b, max)) return false;
    out.assign(b.begin(), b.end());
    return true;
  }
  size_t left() const { return in_.size() - at_; }
  size_t at() const { return at_; }

 private:
  std::span<const uint8_t> in_;
  size_t at_ = 0;
};

std::vector<uint8_t> header_bytes(const SessionHeader& h) {
  std::vector<uint8_t> fields;
  Writer f(fields);
  const hal::DeviceInfo& d = h.device;
  f.str(d.backend);
  f.str(d.path);
  f.str(d.name);
  f.str(d.manufacturer);
  f.str(d.serial);
  f.num(d.vendor_id);
  f.num(d.product_id);
  f.num(d.usage_page);
  f.num(d.usage);
  f.blob(d.report_descriptor);
  f.str(h.normalizer_config);
  f.num(h.created_unix_ns);

  std::vector<uint8_t> out(std::begin(kSessionMagic), std::end(kSessionMagic));
  Writer w(out);
  w.num(kSessionVersion);
  w.num(uint16_t{0});
  w.num(static_cast<uint32_t>(fields.size()));
  w.bytes(fields);
  w.num(crc(fields));
  return out;
}

// One record: kind, flags, payload length, time, payload, CRC of all before.
void append_raw(uint8_t kind, uint8_t flags, int64_t t, std::span<const uint8_t> payload,
                std::vector<uint8_t>& out) {
  const size_t start = out.size();
  Writer w(out);
  w.num(kind);
  w.num(flags);
  w.num(static_cast<uint16_t>(payload.size()));
  w.num(t);
  w.bytes(payload);
  w.num(crc({out.data() + start, out.size() - start}));
}

void append_tool_voxels(int64_t t, const ToolVoxels& tool, std::vector<uint8_t>& out) {
  std::vector<uint8_t> blob;
  Writer b(blob);
  for (uint16_t d : tool.dims)
    b.num(d);
  for (float p : tool.pivot)
    b.num(p);
  b.num(tool.hardness);
  b.bytes(tool.density);
  for (size_t at = 0; at < blob.size(); at += kToolChunkBytes) {
    const size_t n = std::min(kToolChunkBytes, blob.size() - at);
    const uint8_t flags =
        (at == 0 ? kToolChunkFirst : 0) | (at + n == blob.size() ? kToolChunkLast : 0);
    append_raw(kToolChunkRecord, flags, t, {blob.data() + at, n}, out);
  }
}

// The tool a kToolVoxels command's chunks held; an empty string, or why not.
std::string decode_tool_voxels(std::span<const uint8_t> blob, ToolVoxels& tool) {
  Reader b(blob);
  for (uint16_t& d : tool.dims)
    if (!b.num(d)) return "tool record too short";
  for (float& p : tool.pivot)
    if (!b.num(p)) return "tool record too short";
  if (!b.num(tool.hardness)) return "tool record too short";
  std::span<const uint8_t> density;
  b.bytes(b.left(), density);
  tool.density.assign(density.begin(), density.end());
  if (auto why = tool_voxels_problem(tool)) return "tool_voxels command: " + *why;
  return {};
}

void append_record(const SessionRecord& r, std::vector<uint8_t>& out) {
  if (r.kind == SessionRecord::Kind::kCommand && r.command.kind == CommandKind::kToolVoxels &&
      r.command.voxels != nullptr) {
    append_tool_voxels(r.t_ns(), *r.command.voxels, out);
    return;
  }
  std::vector<uint8_t> payload;
  Writer p(payload);
  uint8_t kind = 0;
  uint8_t flags = 0;
  if (r.kind == SessionRecord::Kind::kHaptic) {
    const HapticRecord& h = r.haptic;
    switch (h.type) {
      case HapticRecord::Type::kStart:
        kind = kHapticStartRecord;
        p.bytes({reinterpret_cast<const uint8_t*>(h.settings.data()), h.settings.size()});
        break;
      case HapticRecord::Type::kPatch:
        kind = kHapticPatchRecord;
        p.num(h.tag);
        for (int i = 0; i < 3; ++i)
          p.num(h.values[i]);
        break;
      case HapticRecord::Type::kTick:
        kind = kHapticTickRecord;
        p.num(h.tick_t_ns);
        p.num(h.index);
        p.num(h.buttons);
        p.num(h.flags);
        p.num(h.tag);
        for (float v : h.values)
          p.num(v);
        break;
    }
  } else if (r.kind == SessionRecord::Kind::kCommand) {
    kind = kCommandRecord;
    p.num(static_cast<uint8_t>(r.command.kind));
    p.num(r.command.choice);
    for (int i = 0; i < Command::value_count(r.command.kind); ++i)
      p.num(r.command.values[i]);
  } else {
    const hal::RawEvent& e = r.event;
    switch (e.kind) {
      case hal::RawEventKind::kReport:
        kind = kReportRecord;
        flags = e.truncated ? 1 : 0;
        p.bytes(e.bytes());
        break;
      case hal::RawEventKind::kAxis:
      case hal::RawEventKind::kButton:
        kind = e.kind == hal::RawEventKind::kAxis ? kAxisRecord : kButtonRecord;
        p.num(e.index);
        p.num(e.value);
        break;
      case hal::RawEventKind::kSync:
        kind = kSyncRecord;
        break;
      case hal::RawEventKind::kRemoved:
        kind = kRemovedRecord;
        break;
    }
  }
  append_raw(kind, flags, r.t_ns(), payload, out);
}

// Decodes one record's payload; an empty string on success, else why not.
std::string decode_record(uint8_t kind, uint8_t flags, int64_t t, std::span<const uint8_t> payload,
                          SessionRecord& out) {
  Reader p(payload);
  switch (kind) {
    case kReportRecord:
      if (payload.size() > hal::RawEvent::kMaxReportBytes) return "report longer than 64 bytes";
      out = SessionRecord::of(hal::RawEvent::report(t, payload));
      out.event.truncated = (flags & 1) != 0;
      return {};
    case kAxisRecord:
    case kButtonRecord: {
      int32_t index, value;
      if (payload.size() != 8 || !p.num(index) || !p.num(value))
        return "axis/button record of wrong size";
      if (index < 0 || index > 63) return "axis/button index out of range";
      out = SessionRecord::of(kind == kAxisRecord ? hal::RawEvent::axis(t, index, value)
                                                  : hal::RawEvent::button(t, index, value != 0));
      return {};
    }
    case kSyncRecord:
    case kRemovedRecord:
      if (!payload.empty()) return "sync/removed record with a payload";
      out = SessionRecord::of(kind == kSyncRecord ? hal::RawEvent::sync(t)
                                                  : hal::RawEvent::removed(t));
      return {};
    case kHapticStartRecord:
    case kHapticPatchRecord:
    case kHapticTickRecord: {
      HapticRecord h;
      if (kind == kHapticStartRecord) {
        h.type = HapticRecord::Type::kStart;
        h.settings.assign(payload.begin(), payload.end());
      } else if (kind == kHapticPatchRecord) {
        h.type = HapticRecord::Type::kPatch;
        if (payload.size() != 20) return "haptic patch record of wrong size";
        p.num(h.tag);
        for (int i = 0; i < 3; ++i)
          p.num(h.values[i]);
      } else {
        h.type = HapticRecord::Type::kTick;
        if (payload.size() != 49) return "haptic tick record of wrong size";
        p.num(h.tick_t_ns);
        p.num(h.index);
        p.num(h.buttons);
        p.num(h.flags);
        p.num(h.tag);
        for (float& v : h.values)
          p.num(v);
      }
      if (auto why = haptic_problem(h))
        return "haptic " + std::string(haptic_record_name(h.type)) + " record: " + *why;
      out = SessionRecord::of(t, h);
      return {};
    }
    case kCommandRecord: {
      uint8_t command_kind;
      Command c;
      if (!p.num(command_kind) || !p.num(c.choice)) return "command record too short";
      if (command_kind < 1 || command_kind > kCommandKindCount) {
        return "unknown command " + std::to_string(command_kind);
      }
      c.kind = static_cast<CommandKind>(command_kind);
      const int n = Command::value_count(c.kind);
      if (p.left() != sizeof(float) * static_cast<size_t>(n)) return "command record of wrong size";
      for (int i = 0; i < n; ++i)
        p.num(c.values[i]);
      if (auto why = command_problem(c))
        return std::string(command_name(c.kind)) + " command: " + *why;
      out = SessionRecord::of(t, c);
      return {};
    }
    default:
      return "unknown record kind " + std::to_string(kind);
  }
}

}  // namespace

Result<Session> parse_session_bytes(std::span<const uint8_t> bytes, const std::string& name,
                                    SessionReadInfo* info) {
  if (bytes.size() < sizeof(kSessionMagic) ||
      std::memcmp(bytes.data(), kSessionMagic, sizeof(kSessionMagic)) != 0) {
    return Error(name + ": not a sculpt session file (bad magic)");
  }
  Reader r(bytes.subspan(sizeof(kSessionMagic)));
  uint16_t version, flags;
  uint32_t n;
  if (!r.num(version) || !r.num(flags) || !r.num(n)) return Error(name + ": truncated header");
  if (version != kSessionVersion) {
    return Error(name + ": session version " + std::to_string(version) +
                 " is not supported (this build reads " + std::to_string(kSessionVersion) + ")");
  }
  if (n > kMaxHeaderBytes)
    return Error(name + ": header length " + std::to_string(n) + " is absurd");
  std::span<const uint8_t> fields;
  uint32_t header_crc;
  if (!r.bytes(n, fields) || !r.num(header_crc)) return Error(name + ": truncated header");
  if (crc(fields) != header_crc) return Error(name + ": header checksum mismatch (damaged file)");

  Session s;
  Reader f(fields);
  hal::DeviceInfo& d = s.header.device;
  const bool fields_ok =
      f.str(d.backend, kMaxBackendBytes) && f.str(d.path, kMaxDeviceTextBytes) &&
      f.str(d.name, kMaxDeviceTextBytes) && f.str(d.manufacturer, kMaxDeviceTextBytes) &&
      f.str(d.serial, kMaxDeviceTextBytes) && f.num(d.vendor_id) && f.num(d.product_id) &&
      f.num(d.usage_page) && f.num(d.usage) && f.blob(d.report_descriptor, kMaxDescriptorBytes) &&
      f.str(s.header.normalizer_config, kMaxNormalizerBytes) && f.num(s.header.created_unix_ns) &&
      f.left() == 0;
  if (!fields_ok) return Error(name + ": malformed header fields");

  const size_t records_start = sizeof(kSessionMagic) + r.at();
  size_t at = records_start;
  std::string problem;
  int64_t last_t = INT64_MIN;
  // A tool's chunks so far: where its first began (npos: none), its time.
  size_t tool_start = std::string::npos;
  int64_t tool_t = 0;
  std::vector<uint8_t> tool_blob;
  constexpr size_t kMaxToolBlobBytes =
      kToolHeadBytes + size_t{kMaxToolVoxelsEdge} * kMaxToolVoxelsEdge * kMaxToolVoxelsEdge;
  while (at < bytes.size()) {
    Reader rec(bytes.subspan(at));
    uint8_t kind, rflags;
    uint16_t len;
    int64_t t;
    std::span<const uint8_t> payload;
    uint32_t record_crc;
    if (!rec.num(kind) || !rec.num(rflags) || !rec.num(len) || !rec.num(t) ||
        !rec.bytes(len, payload) || !rec.num(record_crc)) {
      problem = "cut off in the middle of record " + std::to_string(s.records.size() + 1);
      break;
    }
    if (crc(bytes.subspan(at, kRecordHeadBytes + len)) != record_crc) {
      problem = "checksum mismatch in record " + std::to_string(s.records.size() + 1);
      break;
    }
    if (t < last_t) {
      problem = "record " + std::to_string(s.records.size() + 1) + " goes back in time";
      break;
    }
    const std::string where = "record " + std::to_string(s.records.size() + 1) + ": ";
    if (kind == kToolChunkRecord) {
      // A tool's chunks, one after another at one time, become one command.
      const bool first = (rflags & kToolChunkFirst) != 0;
      if (first != (tool_start == std::string::npos) || (!first && t != tool_t) ||
          (rflags & ~(kToolChunkFirst | kToolChunkLast)) != 0) {
        problem = where + "tool record out of sequence";
        break;
      }
      if (first) {
        tool_start = at;
        tool_t = t;
        tool_blob.clear();
      }
      if (tool_blob.size() + payload.size() > kMaxToolBlobBytes) {
        problem = where + "tool record larger than the largest tool";
        break;
      }
      tool_blob.insert(tool_blob.end(), payload.begin(), payload.end());
      last_t = t;
      at += rec.at();
      if ((rflags & kToolChunkLast) == 0) continue;
      auto tool = std::make_shared<ToolVoxels>();
      if (std::string why = decode_tool_voxels(tool_blob, *tool); !why.empty()) {
        problem = where + why;
        at = tool_start;
        break;
      }
      Command c{CommandKind::kToolVoxels};
      c.voxels = std::move(tool);
      s.records.push_back(SessionRecord::of(t, c));
      tool_start = std::string::npos;
      tool_blob = {};
      continue;
    }
    if (tool_start != std::string::npos) {
      problem = where + "a tool record is cut short by another record";
      at = tool_start;
      break;
    }
    SessionRecord record;
    if (std::string why = decode_record(kind, rflags, t, payload, record); !why.empty()) {
      problem = where + why;
      break;
    }
    s.records.push_back(record);
    last_t = t;
    at += rec.at();
  }
  if (problem.empty() && tool_start != std::string::npos)
    problem = "cut off in the middle of the tool of record " + std::to_string(s.records.size() + 1);
  // A tool's records before the problem are lost with it.
  if (tool_start != std::string::npos) at = tool_start;
  if (info != nullptr) {
    info->records = static_cast<int64_t>(s.records.size());
    info->bytes_lost = static_cast<int64_t>(bytes.size() - at);
    info->warning = problem.empty()
                        ? std::string()
                        : name + ": " + problem + "; replaying the " +
                              std::to_string(s.records.size()) + " records before it, " +
                              std::to_string(info->bytes_lost) + " bytes lost";
  }
  return s;
}

Result<Session> read_session_file(const std::filesystem::path& path, SessionReadInfo* info) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) return Error(path.string() + ": cannot open: " + ec.message());
  // Sessions are read whole; the limit keeps a wrong path (a disk image, say)
  // from exhausting memory. An hour at 1 kHz is about 100 MB.
  constexpr uintmax_t kMaxSessionBytes = uintmax_t{4} << 30;
  if (size > kMaxSessionBytes)
    return Error(path.string() + ": too large for a session (" + std::to_string(size) + " bytes)");
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error(path.string() + ": cannot open: " + std::strerror(errno));
  std::vector<uint8_t> bytes(static_cast<size_t>(size));
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!in) return Error(path.string() + ": read failed");
  return parse_session_bytes(bytes, path.string(), info);
}

std::vector<uint8_t> serialize_session(const Session& session) {
  std::vector<uint8_t> out = header_bytes(session.header);
  for (const SessionRecord& r : session.records)
    append_record(r, out);
  return out;
}

Status write_session_file(const std::filesystem::path& path, const Session& session) {
  for (size_t i = 0; i < session.records.size(); ++i)
    if (Status st = check_writable(session.records[i], path.string(), static_cast<int64_t>(i)); !st)
      return st;
  AtomicFileWriter out(path);
  const std::vector<uint8_t> bytes = serialize_session(session);
  out.write(bytes.data(), bytes.size());
  return out.commit();
}

Result<SessionWriter> SessionWriter::create(const std::filesystem::path& path,
                                            const SessionHeader& header) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return Error(path.string() + ": cannot create: " + std::strerror(errno));
  SessionWriter w(fd, path.string());
  if (Status st = w.write_all(header_bytes(header)); !st) return st.error();
  if (Status st = w.sync(); !st) return st.error();
  return w;
}

SessionWriter::SessionWriter(int fd, std::string name)
    : fd_(fd), name_(std::move(name)), last_sync_(std::chrono::steady_clock::now()) {}

SessionWriter::SessionWriter(SessionWriter&& o) noexcept
    : fd_(std::exchange(o.fd_, -1)),
      name_(std::move(o.name_)),
      records_(o.records_),
      last_t_ns_(o.last_t_ns_),
      last_sync_(o.last_sync_) {}

SessionWriter& SessionWriter::operator=(SessionWriter&& o) noexcept {
  if (this != &o) {
    (void)close();
    fd_ = std::exchange(o.fd_, -1);
    name_ = std::move(o.name_);
    records_ = o.records_;
    last_t_ns_ = o.last_t_ns_;
    last_sync_ = o.last_sync_;
  }
  return *this;
}

SessionWriter::~SessionWriter() {
  (void)close();
}

Status SessionWriter::write_all(std::span<const uint8_t> bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd_, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return Error(name_ + ": write failed: " + std::strerror(errno));
    bytes = bytes.subspan(static_cast<size_t>(n));
  }
  return {};
}

Status SessionWriter::sync() {
  if (::fdatasync(fd_) != 0) return Error(name_ + ": sync failed: " + std::strerror(errno));
  last_sync_ = std::chrono::steady_clock::now();
  return {};
}

Status SessionWriter::append(const SessionRecord& record) {
  if (fd_ < 0) return Error(name_ + ": recording is closed");
  if (record.t_ns() < last_t_ns_) return Error(name_ + ": record goes back in time");
  if (Status st = check_writable(record, name_, records_); !st) return st;
  std::vector<uint8_t> bytes;
  append_record(record, bytes);
  if (Status st = write_all(bytes); !st) return st;
  ++records_;
  last_t_ns_ = record.t_ns();
  return sync_if_due();
}

Status SessionWriter::sync_if_due() {
  if (fd_ < 0) return {};
  if (std::chrono::steady_clock::now() - last_sync_ < kSyncInterval) return {};
  return sync();
}

Status SessionWriter::close() {
  if (fd_ < 0) return {};
  Status st = sync();
  ::close(fd_);
  fd_ = -1;
  return st;
}

}  // namespace sculpt::sim
