#pragma once
// A sink that keeps a run's findings compactly while the model they are about is still alive.
// A generated model can have a finding per link; as Diagnostics (a 200-byte struct and one or
// two heap strings each) they were the third largest cost of bodycheck's peak, next to the
// model. Here a finding is a small fixed record; its message lives in large text blocks, as
// the part that differs from the rule's previous message (a generated model's findings differ
// in a link name and a number or two); rule ids and categories are interned, and a hint equal
// to the last one of the same rule is kept once.
// The Diagnostics come back, in arrival order, once the model is gone.

#include <bodyfmt/diagnostic.h>

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace bodyfmt::tools {

class CompactFindings : public DiagnosticSink {
 public:
  void report(Diagnostic diagnostic) override;

  std::size_t size() const { return records_.size(); }

  /// Every finding as reported, in arrival order; the store is empty afterwards. Text blocks
  /// are freed as soon as the findings that use them are rebuilt.
  std::vector<Diagnostic> take();

 private:
  /// A message in the text blocks: the lengths of the prefix and the suffix it shares with the
  /// rule's previous message (two varints), then the bytes between them.
  struct Text {
    std::uint32_t block = 0;
    std::uint32_t offset = 0;
    std::uint32_t size = 0;
  };
  struct Record {
    SourceLocation location;
    Text message;
    std::uint32_t hint = 0;      ///< index into hints_ (0: none)
    std::uint16_t rule = 0;      ///< index into rules_
    std::uint16_t category = 0;  ///< index into categories_
    Severity severity = Severity::kError;
    /// Index into rare_ for the parts most findings lack (an alias site, fix-its), or -1.
    std::int32_t rare = -1;
  };
  struct Rare {
    std::optional<SourceLocation> via;
    std::vector<FixIt> fixes;
  };

  Text store(std::uint16_t rule, std::string_view message);
  void append(std::string_view bytes);
  std::uint32_t keep_hint(std::uint16_t rule, std::string&& hint);
  static std::uint16_t intern(std::vector<std::string>& table, const std::string& value);

  std::deque<Record> records_;
  std::vector<std::unique_ptr<char[]>> blocks_;
  std::size_t used_in_last_block_ = 0;
  std::vector<std::string> rules_;
  std::vector<std::string> categories_{""};
  std::map<std::uint16_t, std::string> last_message_of_rule_;
  std::vector<std::string> hints_{""};
  std::map<std::uint16_t, std::uint32_t> last_hint_of_rule_;
  std::vector<Rare> rare_;
};

}  // namespace bodyfmt::tools
