#include "replay.h"

#include "trac0r/input_checks.h"
#include "trac0r/input_file.h"

#include <SDL.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>

namespace trac0r_viewer {

namespace {

using Type = ReplayCommand::Type;

std::string trim(const std::string& s) {
    const std::size_t first = s.find_first_not_of(" \t\r");
    if (first == std::string::npos) {
        return "";
    }
    const std::size_t last = s.find_last_not_of(" \t\r");
    return s.substr(first, last - first + 1);
}

// One line's reader: every failure names the file and the line, and then
// the argument it could not read, or the whole line.
class LineParser {
  public:
    LineParser(const std::string& origin, int line, const std::string& text)
        : where_(origin + ":" + std::to_string(line) + ": "), text_(text) {}

    [[noreturn]] void fail(const std::string& what) const { fail_at(what, text_); }
    [[noreturn]] void fail_at(const std::string& what, const std::string& got) const {
        throw ReplayError(where_ + what + ", got '" + trac0r::printable(got, 80) + "'");
    }

    long integer(const std::string& argument, long min, long max) const {
        std::istringstream in(argument);
        long value = 0;
        std::string rest;
        if (!(in >> value) || (in >> rest) || value < min || value > max) {
            fail_at(
                "expected an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]",
                argument);
        }
        return value;
    }

    long key(const std::string& name) const {
        const SDL_Keycode code = SDL_GetKeyFromName(name.c_str());
        if (name.empty() || code == SDLK_UNKNOWN) {
            fail_at("expected an SDL key name (W, F1, Escape, Space, Left Shift, Keypad +, ...)",
                    name);
        }
        return code;
    }

    long button(const std::string& name) const {
        const std::map<std::string, long> buttons = {
            {"left", SDL_BUTTON_LEFT}, {"middle", SDL_BUTTON_MIDDLE}, {"right", SDL_BUTTON_RIGHT}};
        const auto b = buttons.find(name);
        if (b == buttons.end()) {
            fail_at("expected a mouse button: left, middle or right", name);
        }
        return b->second;
    }

  private:
    std::string where_;
    std::string text_;
};

std::vector<ReplayCommand> parse_line(const LineParser& p, const std::string& command,
                                      const std::string& argument, long* timeout_ms) {
    ReplayCommand c;
    if (command == "wait_timeout") {
        *timeout_ms = 1000 * p.integer(argument, 1, 24 * 3600);
        return {};
    }
    if (command == "wait") {
        c.type = Type::wait;
        c.value = p.integer(argument, 0, 3600 * 1000);
    } else if (command == "wait_spp") {
        c.type = Type::wait_spp;
        c.value = p.integer(argument, 1, 1L << 31);
        c.timeout_ms = *timeout_ms;
    } else if (command == "key") {
        ReplayCommand down;
        down.type = Type::key_down;
        down.value = p.key(argument);
        ReplayCommand up = down;
        up.type = Type::key_up;
        return {down, up};
    } else if (command == "key_down" || command == "key_up") {
        c.type = command == "key_down" ? Type::key_down : Type::key_up;
        c.value = p.key(argument);
    } else if (command == "mouse_move") {
        std::istringstream in(argument);
        std::string x;
        std::string y;
        std::string rest;
        if (!(in >> x >> y) || (in >> rest)) {
            p.fail("mouse_move: expected two integers X Y");
        }
        c.type = Type::mouse_move;
        c.x = static_cast<int>(p.integer(x, -100000, 100000));
        c.y = static_cast<int>(p.integer(y, -100000, 100000));
    } else if (command == "resize") {
        std::istringstream in(argument);
        std::string w;
        std::string h;
        std::string rest;
        if (!(in >> w >> h) || (in >> rest)) {
            p.fail("resize: expected two integers W H");
        }
        c.type = Type::resize;
        c.x = static_cast<int>(p.integer(w, 16, 16384));
        c.y = static_cast<int>(p.integer(h, 16, 16384));
        c.timeout_ms = *timeout_ms;
    } else if (command == "mouse_down" || command == "mouse_up") {
        c.type = command == "mouse_down" ? Type::mouse_down : Type::mouse_up;
        c.value = p.button(argument);
    } else if (command == "wheel") {
        c.type = Type::wheel;
        c.value = p.integer(argument, -1000, 1000);
    } else {
        p.fail("unknown command '" + command +
               "' (expected wait, wait_spp, wait_timeout, key, key_down, key_up, mouse_move, "
               "mouse_down, mouse_up, wheel or resize)");
    }
    return {c};
}

std::uint16_t modifier_of(SDL_Keycode key) {
    switch (key) {
    case SDLK_LSHIFT:
        return KMOD_LSHIFT;
    case SDLK_RSHIFT:
        return KMOD_RSHIFT;
    case SDLK_LCTRL:
        return KMOD_LCTRL;
    case SDLK_RCTRL:
        return KMOD_RCTRL;
    case SDLK_LALT:
        return KMOD_LALT;
    case SDLK_RALT:
        return KMOD_RALT;
    default:
        return 0;
    }
}

}  // namespace

std::vector<ReplayCommand> parse_replay(const std::string& text, const std::string& origin) {
    std::vector<ReplayCommand> commands;
    std::istringstream in(text);
    std::string raw;
    int line = 0;
    long timeout_ms = ReplayCommand().timeout_ms;
    while (std::getline(in, raw)) {
        ++line;
        const std::string content = trim(raw.substr(0, raw.find('#')));
        if (content.empty()) {
            continue;
        }
        // A NUL would end a key name early for SDL ("W\0..." is W), and
        // any control byte means this is no script (a binary file, UTF-16).
        if (std::any_of(content.begin(), content.end(), [](char ch) {
                const unsigned char u = static_cast<unsigned char>(ch);
                return (u < 0x20 && ch != '\t') || u == 0x7F;
            })) {
            LineParser(origin, line, content).fail("expected a line of text (a binary file?)");
        }
        // The argument is the rest of the line: key names may hold spaces.
        const std::size_t space = content.find_first_of(" \t");
        const std::string command = content.substr(0, space);
        const std::string argument = space == std::string::npos ? "" : trim(content.substr(space));
        const LineParser parser(origin, line, content);
        for (ReplayCommand c : parse_line(parser, command, argument, &timeout_ms)) {
            c.line = line;
            commands.push_back(c);
        }
    }
    return commands;
}

std::vector<ReplayCommand> load_replay(const std::string& path) {
    // Only a regular file will do: a directory would read as an empty
    // script, and /dev/zero or a FIFO would never end.
    std::string text;
    try {
        text = trac0r::read_input_file(path, "replay script");
    } catch (const std::runtime_error& e) {
        throw ReplayError(std::string("--replay ") + e.what());
    }
    return parse_replay(text, path);
}

void check_replay_reachable(const std::vector<ReplayCommand>& commands, const std::string& origin,
                            long max_spp) {
    for (const ReplayCommand& c : commands) {
        if (max_spp > 0 && c.type == Type::wait_spp && c.value > max_spp) {
            throw ReplayError(origin + ":" + std::to_string(c.line) + ": wait_spp " +
                              std::to_string(c.value) + " cannot be reached: the window stops at " +
                              std::to_string(max_spp) + " spp (--spp)");
        }
    }
}

ReplayPlayer::ReplayPlayer(std::vector<ReplayCommand> commands, std::string origin)
    : commands_(std::move(commands)), origin_(std::move(origin)) {}

void ReplayPlayer::step(std::uint32_t window_id, std::uint32_t now_ms, long shown_spp) {
    if (awaiting_marker_) {
        return;  // the window has not handled the last batch yet
    }
    if (resizing_) {
        int w = 0;
        int h = 0;
        SDL_GetWindowSize(SDL_GetWindowFromID(window_id), &w, &h);
        if (w != resizing_->x || h != resizing_->y) {
            if (now_ms - wait_started_ms_ >= static_cast<std::uint32_t>(resizing_->timeout_ms)) {
                throw ReplayError(
                    origin_ + ":" + std::to_string(resizing_->line) + ": resize " +
                    std::to_string(resizing_->x) + " " + std::to_string(resizing_->y) +
                    ": the window is still " + std::to_string(w) + " x " + std::to_string(h) +
                    " after " + std::to_string(resizing_->timeout_ms / 1000) + " s (wait_timeout)");
            }
            return;
        }
        resizing_ = nullptr;
        push_marker(window_id);  // the window sees the new size before what follows
        return;
    }
    int pushed = 0;
    while (next_ < commands_.size()) {
        const ReplayCommand& c = commands_[next_];
        const bool is_wait = c.type == Type::wait || c.type == Type::wait_spp;
        if ((is_wait && pushed > 0) || pushed == kBatchEvents) {
            // The window handles the events first: a wait_spp right after a
            // camera change must see the new view's samples, not the old.
            push_marker(window_id);
            return;
        }
        if (c.type == Type::wait) {
            if (!waiting_) {
                waiting_ = true;
                wait_started_ms_ = now_ms;
            }
            if (now_ms - wait_started_ms_ < static_cast<std::uint32_t>(c.value)) {
                return;
            }
            waiting_ = false;
        } else if (c.type == Type::wait_spp) {
            if (shown_spp < c.value) {
                if (!waiting_) {
                    waiting_ = true;
                    wait_started_ms_ = now_ms;
                }
                if (now_ms - wait_started_ms_ >= static_cast<std::uint32_t>(c.timeout_ms)) {
                    throw_wait_timeout(c, shown_spp);
                }
                return;
            }
            waiting_ = false;
        } else {
            push(window_id, c);
            ++pushed;
            if (c.type == Type::resize) {
                resizing_ = &c;
                wait_started_ms_ = now_ms;
                ++next_;
                return;
            }
        }
        ++next_;
    }
    if (pushed > 0) {
        push_marker(window_id);  // finished() only once the window has seen all
    }
}

void ReplayPlayer::throw_wait_timeout(const ReplayCommand& c, long shown_spp) const {
    std::string why;
    if (!held_.empty()) {
        why = "; keys held down:";
        for (SDL_Keycode k : held_) {
            why += std::string(" ") + SDL_GetKeyName(k);
        }
        why += " (a held movement key moves the view every frame: key_up it first)";
    }
    throw ReplayError(origin_ + ":" + std::to_string(c.line) + ": wait_spp " +
                      std::to_string(c.value) + " not reached in " +
                      std::to_string(c.timeout_ms / 1000) + " s (wait_timeout): the view shows " +
                      std::to_string(shown_spp) + " spp at full resolution" + why);
}

void ReplayPlayer::push_marker(std::uint32_t window_id) {
    if (marker_type_ == 0) {
        marker_type_ = SDL_RegisterEvents(1);
        if (marker_type_ == static_cast<std::uint32_t>(-1)) {
            throw ReplayError("--replay: SDL has no user event type left");
        }
    }
    SDL_Event e;
    SDL_zero(e);
    e.type = marker_type_;
    e.user.windowID = window_id;
    e.user.timestamp = SDL_GetTicks();
    if (SDL_PushEvent(&e) < 0) {
        std::fprintf(stderr, "trac0r_viewer: --replay: cannot push an event: %s\n", SDL_GetError());
        return;  // nothing would ever hand it back
    }
    awaiting_marker_ = true;
}

bool ReplayPlayer::handled(const SDL_Event& e) {
    if (marker_type_ == 0 || e.type != marker_type_) {
        return false;
    }
    awaiting_marker_ = false;
    return true;
}

void ReplayPlayer::push(std::uint32_t window_id, const ReplayCommand& c) {
    SDL_Event e;
    SDL_zero(e);
    switch (c.type) {
    case Type::key_down:
    case Type::key_up: {
        const SDL_Keycode key = static_cast<SDL_Keycode>(c.value);
        const bool down = c.type == Type::key_down;
        held_.erase(std::remove(held_.begin(), held_.end(), key), held_.end());
        if (down) {
            modifiers_ = static_cast<std::uint16_t>(modifiers_ | modifier_of(key));
            held_.push_back(key);
        } else {
            modifiers_ = static_cast<std::uint16_t>(modifiers_ & ~modifier_of(key));
        }
        e.type = down ? SDL_KEYDOWN : SDL_KEYUP;
        e.key.windowID = window_id;
        e.key.state = down ? SDL_PRESSED : SDL_RELEASED;
        e.key.keysym.sym = key;
        e.key.keysym.scancode = SDL_GetScancodeFromKey(key);
        e.key.keysym.mod = modifiers_;
        break;
    }
    case Type::mouse_move:
        e.type = SDL_MOUSEMOTION;
        e.motion.windowID = window_id;
        e.motion.state = mouse_buttons_;
        e.motion.x = c.x;
        e.motion.y = c.y;
        e.motion.xrel = c.x - mouse_x_;
        e.motion.yrel = c.y - mouse_y_;
        mouse_x_ = c.x;
        mouse_y_ = c.y;
        break;
    case Type::mouse_down:
    case Type::mouse_up: {
        const bool down = c.type == Type::mouse_down;
        const std::uint32_t mask = SDL_BUTTON(static_cast<int>(c.value));
        mouse_buttons_ = down ? (mouse_buttons_ | mask) : (mouse_buttons_ & ~mask);
        e.type = down ? SDL_MOUSEBUTTONDOWN : SDL_MOUSEBUTTONUP;
        e.button.windowID = window_id;
        e.button.button = static_cast<std::uint8_t>(c.value);
        e.button.state = down ? SDL_PRESSED : SDL_RELEASED;
        e.button.clicks = 1;
        e.button.x = mouse_x_;
        e.button.y = mouse_y_;
        break;
    }
    case Type::wheel:
        e.type = SDL_MOUSEWHEEL;
        e.wheel.windowID = window_id;
        e.wheel.y = static_cast<std::int32_t>(c.value);
        e.wheel.direction = SDL_MOUSEWHEEL_NORMAL;
        break;
    case Type::resize:
        // Not an event: the window system answers with its own.
        SDL_SetWindowSize(SDL_GetWindowFromID(window_id), c.x, c.y);
        return;
    case Type::wait:
    case Type::wait_spp:
        return;
    }
    e.common.timestamp = SDL_GetTicks();
    if (SDL_PushEvent(&e) < 0) {
        std::fprintf(stderr, "trac0r_viewer: --replay: cannot push an event: %s\n", SDL_GetError());
    }
}

}  // namespace trac0r_viewer
