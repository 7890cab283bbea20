#include "server/store_files.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstring>

#include "absl/strings/str_cat.h"

namespace membrane::server {
namespace {

std::string ErrnoText(int error) { return std::strerror(error); }

// Closes a descriptor on every way out.
class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  ~Descriptor() {
    if (fd_ >= 0) close(fd_);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int get() const { return fd_; }
  // Closes now; false (errno set) when close reports an error, which for a written file can
  // be the write's own (NFS, quotas).
  bool Close() {
    const int fd = fd_;
    fd_ = -1;
    return close(fd) == 0;
  }

 private:
  int fd_;
};

bool WriteAll(int fd, absl::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = write(fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) errno = EIO;
      return false;
    }
    bytes.remove_prefix(static_cast<size_t>(n));
  }
  return true;
}

class PosixFiles final : public StoreFiles {
 public:
  absl::Status MakeDirectory(const std::string& dir) override {
    if (mkdir(dir.c_str(), 0700) == 0 || errno == EEXIST) return absl::OkStatus();
    return absl::UnavailableError(absl::StrCat("cannot create ", dir, ": ", ErrnoText(errno)));
  }

  absl::StatusOr<std::vector<std::string>> List(const std::string& dir) override {
    DIR* listing = opendir(dir.c_str());
    if (listing == nullptr) {
      return absl::UnavailableError(absl::StrCat("cannot read ", dir, ": ", ErrnoText(errno)));
    }
    std::vector<std::string> names;
    while (const dirent* entry = readdir(listing)) {
      const std::string name = entry->d_name;
      if (name != "." && name != "..") names.push_back(name);
    }
    closedir(listing);
    return names;
  }

  absl::StatusOr<std::string> Read(const std::string& path, int64_t max_bytes) override {
    // O_NOFOLLOW: a link is refused rather than followed; O_NONBLOCK: a FIFO does not wait
    // for a writer before fstat tells what it is.
    Descriptor fd(open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC));
    if (fd.get() < 0) {
      const int error = errno;
      if (error == ELOOP) {
        return absl::FailedPreconditionError(
            absl::StrCat(path, " is a symbolic link, not a regular file"));
      }
      if (error == ENOENT) return absl::NotFoundError(absl::StrCat("no such file: ", path));
      return absl::UnavailableError(absl::StrCat("cannot open ", path, ": ", ErrnoText(error)));
    }
    struct stat info;
    if (fstat(fd.get(), &info) != 0) {
      return absl::UnavailableError(absl::StrCat("cannot stat ", path, ": ", ErrnoText(errno)));
    }
    if (!S_ISREG(info.st_mode)) {
      return absl::FailedPreconditionError(absl::StrCat(path, " is not a regular file"));
    }
    if (info.st_size > max_bytes) {
      return absl::OutOfRangeError(absl::StrCat(path, " holds ", info.st_size,
                                                " bytes, over the limit of ", max_bytes));
    }
    std::string bytes(static_cast<size_t>(info.st_size), '\0');
    size_t done = 0;
    while (done < bytes.size()) {
      const ssize_t n = read(fd.get(), bytes.data() + done, bytes.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        return absl::UnavailableError(absl::StrCat("cannot read ", path, ": ", ErrnoText(errno)));
      }
      if (n == 0) break;  // shrunk meanwhile: what is there is parsed (and found short)
      done += static_cast<size_t>(n);
    }
    bytes.resize(done);
    return bytes;
  }

  absl::Status Write(const std::string& dir, const std::string& path,
                     absl::Span<const absl::string_view> pieces) override {
    const std::string temporary = path + ".tmp";
    const auto failed = [&](const std::string& what, int error) {
      unlink(temporary.c_str());
      return absl::UnavailableError(absl::StrCat(what, ": ", ErrnoText(error)));
    };
    Descriptor fd(open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600));
    if (fd.get() < 0) return failed(temporary, errno);
    for (const absl::string_view piece : pieces) {
      if (!WriteAll(fd.get(), piece)) return failed(temporary, errno);
    }
    if (fsync(fd.get()) != 0) return failed(temporary, errno);
    if (!fd.Close()) return failed(temporary, errno);
    if (rename(temporary.c_str(), path.c_str()) != 0) return failed(path, errno);
    // The rename is durable only once the directory is.
    Descriptor dir_fd(open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
    if (dir_fd.get() < 0 || fsync(dir_fd.get()) != 0) {
      return absl::UnavailableError(absl::StrCat(dir, ": ", ErrnoText(errno)));
    }
    return absl::OkStatus();
  }

  absl::Status Remove(const std::string& path) override {
    if (unlink(path.c_str()) == 0 || errno == ENOENT) return absl::OkStatus();
    return absl::UnavailableError(absl::StrCat("cannot remove ", path, ": ", ErrnoText(errno)));
  }
};

}  // namespace

std::unique_ptr<StoreFiles> PosixStoreFiles() { return std::make_unique<PosixFiles>(); }

}  // namespace membrane::server
