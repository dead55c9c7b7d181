// The window's messages: short texts shown for a few seconds at the bottom
// of the window, the newest few only, and one of each kind (a repeated
// exposure message replaces the last, rather than stacking up).
#ifndef TRAC0R_VIEWER_MESSAGES_H
#define TRAC0R_VIEWER_MESSAGES_H

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace trac0r_viewer {

class MessageList {
  public:
    static constexpr std::size_t most = 3;  // shown at once: the newest

    // `kind` (e.g. "exposure"): replaces the message of that kind, if any;
    // empty: replaces only a message of the same text.
    void add(const std::string& text, const std::string& kind, std::uint32_t until_ms) {
        messages_.erase(std::remove_if(messages_.begin(), messages_.end(),
                                       [&](const Message& m) {
                                           return kind.empty() ? m.text == text : m.kind == kind;
                                       }),
                        messages_.end());
        messages_.push_back({text, kind, until_ms});
        if (messages_.size() > most) {
            messages_.erase(messages_.begin(), messages_.end() - most);
        }
    }
    // Drops those whose time is over; whether any went.
    bool expire(std::uint32_t now_ms) {
        const std::size_t before = messages_.size();
        messages_.erase(std::remove_if(messages_.begin(), messages_.end(),
                                       [&](const Message& m) { return now_ms >= m.until_ms; }),
                        messages_.end());
        return messages_.size() != before;
    }
    bool empty() const { return messages_.empty(); }
    // The messages, oldest first, one a line.
    std::string text() const {
        std::string all;
        for (const Message& m : messages_) {
            all += (all.empty() ? "" : "\n") + m.text;
        }
        return all;
    }

  private:
    struct Message {
        std::string text;
        std::string kind;
        std::uint32_t until_ms;
    };
    std::vector<Message> messages_;
};

}  // namespace trac0r_viewer

#endif
