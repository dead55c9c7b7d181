// What the window writes on top of the image, without a window: the key
// help as it fits a window's size, and the messages at the bottom.
#include <catch2/catch.hpp>

#include "trac0r_viewer/messages.h"
#include "trac0r_viewer/options.h"
#include "trac0r_viewer/overlay.h"

#include <algorithm>
#include <string>

using trac0r_viewer::Font;
using trac0r_viewer::MessageList;

namespace {

int lines(const std::string& text) {
    return text.empty() ? 0 : 1 + static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

bool fits(const Font& font, const std::string& text, int width, int height) {
    int w = 0;
    int h = 0;
    font.panel_size(text, &w, &h);
    return w <= width && h <= height;
}

}  // namespace

TEST_CASE("the key help fits the window: all of it, a short list, or the short list cut",
          "[window_text]") {
    // The font size of a 300-pixel-high window (window_session.cpp).
    const Font font(trac0r_viewer::overlay_font_path(), 10);
    const std::string big = trac0r_viewer::fitting_help(font, 1000, 700);
    const std::string all = trac0r_viewer::key_help_text();
    CHECK(big == "Keys and mouse\n" + all.substr(0, all.size() - 1));  // all of it

    // 400 x 300: the panel has 384 x 284 pixels, or less under the overlay.
    for (int height : {284, 160, 90}) {
        INFO("panel height " << height);
        const std::string help = trac0r_viewer::fitting_help(font, 384, height);
        REQUIRE(!help.empty());
        CHECK(fits(font, help, 384, height));
        CHECK(help.find("W A S D") != std::string::npos);
        CHECK((help.find("screenshot") != std::string::npos || height < 160));
    }
    const std::string cut = trac0r_viewer::fitting_help(font, 384, 90);
    CHECK(cut.find("a larger window shows all") != std::string::npos);
    CHECK(lines(cut) < lines(trac0r_viewer::key_help_short_text()));
    CHECK(trac0r_viewer::fitting_help(font, 384, 20).empty());  // nothing fits
}

TEST_CASE("messages: the newest few, one of each kind", "[window_text]") {
    MessageList m;
    for (int i = 0; i < 7; ++i) {
        m.add("exposure " + std::to_string(i), "exposure", 1000);
    }
    CHECK(m.text() == "exposure 6");  // replaced, not stacked
    m.add("accumulation restarted", "", 1000);
    m.add("accumulation restarted", "", 2000);  // the same text: once
    CHECK(m.text() == "exposure 6\naccumulation restarted");
    m.add("a", "", 1000);
    m.add("b", "", 1000);
    CHECK(m.text() == "accumulation restarted\na\nb");  // the newest MessageList::most
    CHECK(m.expire(1500));
    CHECK(m.text() == "accumulation restarted");
    CHECK_FALSE(m.expire(1500));
    CHECK(m.expire(2000));
    CHECK(m.empty());
}

TEST_CASE("the overlay says how long the accumulation ran, the integrator and the filter",
          "[window_text]") {
    trac0r_viewer::OverlayFigures f;
    f.spp = 40;
    f.accumulation_seconds = 12.34;
    f.integrator = "naive";
    f.filter = true;
    const std::string on = trac0r_viewer::overlay_text(f);
    CHECK(on.find("12.3 s") != std::string::npos);
    CHECK(on.find("naive integrator") != std::string::npos);
    CHECK(on.find("filter on") != std::string::npos);
    f.integrator = "nee";
    f.filter = false;
    const std::string off = trac0r_viewer::overlay_text(f);
    CHECK(off.find("nee integrator") != std::string::npos);
    CHECK(off.find("filter off") != std::string::npos);
}
