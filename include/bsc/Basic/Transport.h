//===- Transport.h - Content-Length framed JSON over descriptors -*- C++ -*-===//
//
// The base protocol of the language server (JSON-RPC) and of the debug
// adapter (DAP): both frame JSON messages the same way.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_BASIC_TRANSPORT_H
#define BSC_BASIC_TRANSPORT_H

#include "llvm/Support/JSON.h"
#include <optional>
#include <string>

namespace bsc {

/// Reads and writes `Content-Length`-framed JSON messages.
class Transport {
public:
  Transport(int InFd, int OutFd) : InFd(InFd), OutFd(OutFd) {}

  enum class Read { Message, Malformed, Timeout, End };
  /// Waits up to `TimeoutMs` (-1: for ever) for the next message. A
  /// message whose body is not JSON is Malformed (Error says why) and
  /// skipped; broken headers are skipped up to the next header.
  Read read(llvm::json::Value &Out, std::string &Error, int TimeoutMs);
  void write(const llvm::json::Value &Message);

private:
  /// Whether a whole message is buffered; takes it out if so.
  std::optional<std::string> takeMessage(std::string &Error, bool &Bad);

  int InFd, OutFd;
  std::string Buffer;
  bool AtEnd = false;
};

} // namespace bsc

#endif
