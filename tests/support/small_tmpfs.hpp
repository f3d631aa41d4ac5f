// A small tmpfs a test mounts itself to fill up (a full disk) or make
// read-only, unmounted on
// scope exit (lazily: a store may still hold its files open). Mounting needs
// root or CAP_SYS_ADMIN: tests skip with why_not() where it is refused.
#pragma once

#include <sys/mount.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

namespace splat::test_support {

class SmallTmpfs {
 public:
  SmallTmpfs(const std::filesystem::path& dir, long size_bytes) : dir_(dir) {
    std::filesystem::create_directories(dir);
    const std::string options = "size=" + std::to_string(size_bytes) + ",mode=0700";
    mounted_ = ::mount("tmpfs", dir.c_str(), "tmpfs", MS_NOSUID | MS_NODEV, options.c_str()) == 0;
    error_ = mounted_ ? 0 : errno;
  }
  ~SmallTmpfs() {
    if (mounted_) ::umount2(dir_.c_str(), MNT_DETACH);
  }
  SmallTmpfs(const SmallTmpfs&) = delete;
  SmallTmpfs& operator=(const SmallTmpfs&) = delete;

  bool mounted() const { return mounted_; }
  // Read-only from now on, for root too (a store nobody may write).
  bool remount_read_only() {
    return ::mount("tmpfs", dir_.c_str(), "tmpfs", MS_REMOUNT | MS_RDONLY | MS_NOSUID | MS_NODEV,
                   nullptr) == 0;
  }
  std::string why_not() const {
    return "cannot mount a tmpfs at " + dir_.string() + " (" + std::strerror(error_) +
           "): a full-disk test needs root or CAP_SYS_ADMIN";
  }

  // Writes blocks to `file` until the file system refuses one (ENOSPC);
  // false if the file cannot be created at all.
  static bool fill(const std::filesystem::path& file) {
    std::FILE* f = std::fopen(file.c_str(), "w");
    if (f == nullptr) return false;
    const std::string block(64 * 1024, 'f');
    while (std::fwrite(block.data(), 1, block.size(), f) == block.size() && std::fflush(f) == 0) {
    }
    std::fclose(f);
    return true;
  }

 private:
  std::filesystem::path dir_;
  bool mounted_ = false;
  int error_ = 0;
};

}  // namespace splat::test_support
