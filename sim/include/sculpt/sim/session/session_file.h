#pragma once
// Binary session files (".scs"), version 1. All integers little endian.
//
//   file    = magic header record*
//   magic   = 89 53 43 53 0D 0A 1A 0A          ("\x89SCS\r\n\x1a\n": a text-mode
//             transfer or a truncated download shows up in the first 8 bytes)
//   header  = u16 version (1), u16 flags (0), u32 n (<= 1 MiB), n bytes of
//             fields, u32 crc32(fields)
//   fields  = str backend, str path, str name, str manufacturer, str serial,
//             u16 vendor, u16 product, u16 usage_page, u16 usage,
//             blob report_descriptor (<= 4096 bytes), str normaliser settings
//             (hal::to_text form), i64 created (ns since the Unix epoch)
//             where str and blob = u32 length + bytes
//   record  = u8 kind, u8 flags, u16 n, i64 t_ns, n bytes of payload,
//             u32 crc32(the 12 bytes before the payload + the payload)
//
// Record kinds and payloads:
//   1 report   the report's bytes (n <= 64); flags bit 0: the device sent more
//   2 axis     i32 index, i32 value       3 button  i32 index, i32 value
//   4 sync     (empty)                    5 removed (empty)
//   6 haptic start  the loop's set-up text (<= 4096 bytes)
//   7 haptic patch  u64 version, f32 x 3 centre (voxels)
//   8 haptic tick   i64 tick time, u32 index, u32 buttons, u8 flags, u64 law
//                   inputs, f32 x 3 position (mm), f32 x 3 force (N)
//   16 command u8 command kind, u8 choice, f32 x (the kind's value count)
// Record times never decrease. Files are append-only: the writer appends each
// record with one write(2), so a crash of the station loses nothing the kernel
// received, and syncs to disk at least every 0.25 s while recording, so a
// power cut or an unplugged disk loses at most that much.
//
// A reader stops at the first record that is cut off, fails its checksum or
// makes no sense, keeps everything before it, and says how much was lost.

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include "sculpt/base/result.h"
#include "sculpt/sim/session/session.h"

namespace sculpt::sim {

inline constexpr uint8_t kSessionMagic[8] = {0x89, 'S', 'C', 'S', '\r', '\n', 0x1a, '\n'};
inline constexpr uint16_t kSessionVersion = 1;

/// What a read kept and lost.
struct SessionReadInfo {
  int64_t records = 0;
  /// Bytes after the last good record (0 for an intact file).
  int64_t bytes_lost = 0;
  /// Why the tail was dropped, one line naming the file; empty when intact.
  std::string warning;
};

/// Parses a whole session from memory (`name` names it in messages). Errors:
/// bad magic, unknown version, damaged header. A damaged tail is dropped and
/// reported in `info`.
Result<Session> parse_session_bytes(std::span<const uint8_t> bytes, const std::string& name,
                                    SessionReadInfo* info = nullptr);
Result<Session> read_session_file(const std::filesystem::path& path,
                                  SessionReadInfo* info = nullptr);

/// The bytes of a whole file (header and records).
std::vector<uint8_t> serialize_session(const Session& session);
/// Writes a whole session at once, atomically (for conversions and generators).
Status write_session_file(const std::filesystem::path& path, const Session& session);

/// Records a live session, append-only (see the top of this file).
class SessionWriter {
 public:
  static constexpr std::chrono::milliseconds kSyncInterval{250};

  /// Creates `path` (replacing it) and writes the header.
  static Result<SessionWriter> create(const std::filesystem::path& path,
                                      const SessionHeader& header);
  SessionWriter(SessionWriter&& other) noexcept;
  SessionWriter& operator=(SessionWriter&& other) noexcept;
  ~SessionWriter();

  /// Appends one record (its time must not be earlier than the previous one's).
  Status append(const SessionRecord& record);
  /// Syncs to disk if the last sync is kSyncInterval old; call it every frame
  /// so a quiet device still gets its last records onto the disk.
  Status sync_if_due();
  /// Syncs and closes. Also done by the destructor (errors then unreported).
  Status close();
  int64_t records() const { return records_; }

 private:
  SessionWriter(int fd, std::string name);
  Status write_all(std::span<const uint8_t> bytes);
  Status sync();

  int fd_ = -1;
  std::string name_;
  int64_t records_ = 0;
  int64_t last_t_ns_ = INT64_MIN;
  std::chrono::steady_clock::time_point last_sync_;
};

}  // namespace sculpt::sim
