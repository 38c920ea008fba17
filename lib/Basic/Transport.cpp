//===- Transport.cpp - Content-Length framed JSON over descriptors --------===//
//
// The base protocol: headers (`Content-Length: N`, others ignored), an
// empty line, N bytes of JSON. Damaged input never stops the server: a
// header block without a length is dropped, a body that is not JSON is
// reported (the server answers with a parse error), and a length beyond
// 64 MiB is refused rather than waited for.
//
//===----------------------------------------------------------------------===//
#include "bsc/Basic/Transport.h"
#include "llvm/ADT/StringExtras.h"
#include <cerrno>
#include <poll.h>
#include <unistd.h>

using namespace bsc;

static constexpr size_t MaxMessageBytes = size_t(64) << 20;

std::optional<std::string> Transport::takeMessage(std::string &Error,
                                                  bool &Bad) {
  Bad = false;
  size_t HeaderEnd = Buffer.find("\r\n\r\n");
  if (HeaderEnd == std::string::npos)
    return std::nullopt;
  llvm::StringRef Headers(Buffer.data(), HeaderEnd);
  std::optional<size_t> Length;
  llvm::SmallVector<llvm::StringRef, 4> Lines;
  Headers.split(Lines, "\r\n");
  for (llvm::StringRef Line : Lines) {
    auto [Name, Value] = Line.split(':');
    size_t N;
    if (Name.trim().equals_insensitive("content-length") &&
        !Value.trim().getAsInteger(10, N))
      Length = N;
  }
  if (!Length || *Length > MaxMessageBytes) {
    Error = Length ? "message longer than 64 MiB"
                   : "message header without a Content-Length";
    Buffer.erase(0, HeaderEnd + 4);
    Bad = true;
    return std::nullopt;
  }
  if (Buffer.size() < HeaderEnd + 4 + *Length)
    return std::nullopt;
  std::string Body = Buffer.substr(HeaderEnd + 4, *Length);
  Buffer.erase(0, HeaderEnd + 4 + *Length);
  return Body;
}

Transport::Read Transport::read(llvm::json::Value &Out, std::string &Error,
                                int TimeoutMs) {
  while (true) {
    bool Bad;
    if (std::optional<std::string> Body = takeMessage(Error, Bad)) {
      llvm::Expected<llvm::json::Value> V = llvm::json::parse(*Body);
      if (!V) {
        Error = llvm::toString(V.takeError());
        return Read::Malformed;
      }
      Out = std::move(*V);
      return Read::Message;
    }
    if (Bad)
      return Read::Malformed;
    if (AtEnd)
      return Read::End;
    pollfd P{InFd, POLLIN, 0};
    int Ready = poll(&P, 1, TimeoutMs);
    if (Ready < 0 && errno == EINTR)
      continue;
    if (Ready == 0)
      return Read::Timeout;
    char Chunk[65536];
    ssize_t N = ::read(InFd, Chunk, sizeof Chunk);
    if (N < 0 && errno == EINTR)
      continue;
    if (N <= 0)
      AtEnd = true;
    else
      Buffer.append(Chunk, N);
  }
}

void Transport::write(const llvm::json::Value &Message) {
  std::string Body;
  llvm::raw_string_ostream(Body) << Message;
  std::string Out = "Content-Length: " + std::to_string(Body.size()) +
                    "\r\n\r\n" + Body;
  const char *P = Out.data();
  size_t Left = Out.size();
  while (Left) {
    ssize_t N = ::write(OutFd, P, Left);
    if (N < 0 && errno == EINTR)
      continue;
    if (N <= 0)
      return; // The client is gone; the next read sees the end.
    P += N;
    Left -= N;
  }
}
