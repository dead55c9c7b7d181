// Scripted input for the window (--replay FILE): the tests' way, and a
// user's, to drive the viewer reproducibly. Input commands become real SDL
// events (SDL_PushEvent) that the window handles exactly as a person's.
//
// One command per line; '#' starts a comment; blank lines are ignored.
//
//   wait MS              pause for MS milliseconds
//   wait_spp N           until the window shows the current view at full
//                        resolution with at least N samples per pixel
//   key NAME             press and release a key
//   key_down NAME        press (and hold) a key
//   key_up NAME          release it
//   mouse_move X Y       move the pointer to window coordinates X, Y
//   mouse_down BUTTON    left, middle or right, at the pointer
//   mouse_up BUTTON
//   wheel N              scroll N notches (positive: away from the user)
//   resize W H           resize the window to W x H (as a user dragging
//                        its edge; the render follows, see docs/viewer.md),
//                        and wait until the window has that size (at most
//                        the wait_timeout)
//   wait_timeout S       later wait_spp commands fail after S seconds
//                        (default 60): the script stops with an error
//                        naming the line, instead of waiting for ever
//
// NAME is an SDL key name: W, F1, Escape, Space, Left Shift, Keypad +, ...
#ifndef TRAC0R_VIEWER_REPLAY_H
#define TRAC0R_VIEWER_REPLAY_H

#include <SDL_events.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace trac0r_viewer {

// A bad replay file: "FILE:LINE: what was expected".
class ReplayError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

struct ReplayCommand {
    enum class Type {
        wait,
        wait_spp,
        key_down,
        key_up,
        mouse_move,
        mouse_down,
        mouse_up,
        wheel,
        resize
    };
    Type type = Type::wait;
    long value = 0;  // milliseconds, samples per pixel, SDL key code, SDL button or notches
    int x = 0;       // mouse_move; resize: the width and height
    int y = 0;
    int line = 0;                 // in the script, for messages
    long timeout_ms = 60 * 1000;  // wait_spp: how long it may wait
};

// Refuses (ReplayError naming the line) a wait_spp the window can never
// reach because it stops at max_spp samples per pixel (0: no limit).
void check_replay_reachable(const std::vector<ReplayCommand>& commands, const std::string& origin,
                            long max_spp);

// Reads and checks the whole file (so a typo fails before a window opens).
std::vector<ReplayCommand> load_replay(const std::string& path);
std::vector<ReplayCommand> parse_replay(const std::string& text, const std::string& origin);

class ReplayPlayer {
  public:
    ReplayPlayer(std::vector<ReplayCommand> commands, std::string origin);

    // Pushes the events of every command that is due, in order, stopping at
    // the first wait that is not over. now_ms: SDL ticks; shown_spp: samples
    // per pixel of the current view on screen (0 while none at full size).
    // Throws ReplayError when a wait_spp runs past its timeout. At most
    // kBatchEvents events go in one batch, so SDL's queue (65,535 events)
    // cannot overflow and drop one (a script's final Escape).
    //
    // A wait only starts once the window has handled every event pushed
    // before it: a batch of events ends with a marker event, and nothing
    // more happens until the window passes that marker to handled(). (The
    // window may leave events queued for a later round, e.g. those after a
    // P; a wait_spp checked before a queued camera change would see the old
    // view's samples.)
    void step(std::uint32_t window_id, std::uint32_t now_ms, long shown_spp);
    // True (and the batch counts as handled) when `e` is the marker event;
    // the window calls it for every event it takes from the queue.
    bool handled(const SDL_Event& e);
    bool finished() const { return next_ >= commands_.size() && !awaiting_marker_; }

  private:
    void push(std::uint32_t window_id, const ReplayCommand& command);
    void push_marker(std::uint32_t window_id);
    [[noreturn]] void throw_wait_timeout(const ReplayCommand& c, long shown_spp) const;

    static constexpr int kBatchEvents = 1000;

    std::vector<ReplayCommand> commands_;
    std::string origin_;
    std::size_t next_ = 0;
    bool waiting_ = false;
    std::uint32_t wait_started_ms_ = 0;
    int mouse_x_ = 0;
    int mouse_y_ = 0;
    std::uint32_t mouse_buttons_ = 0;          // SDL_BUTTON masks
    std::uint16_t modifiers_ = 0;              // KMOD_* of the held keys
    std::vector<SDL_Keycode> held_;            // keys pressed and not released, for messages
    std::uint32_t marker_type_ = 0;            // an SDL user event type, registered on first use
    bool awaiting_marker_ = false;             // pushed events the window has not handled yet
    const ReplayCommand* resizing_ = nullptr;  // a resize the window has not reached yet
};

}  // namespace trac0r_viewer

#endif
