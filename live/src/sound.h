// The feedback sounds of a live session (seed 004 section 5.3.4: a sound with
// every HIT, MISS and TIMEOUT), generated rather than shipped: short sine tones through SDL
// audio. Where no audio device opens (a server, Xvfb in CI), sounds are off and say so once.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace warplab::live {

class FeedbackSounds {
public:
    FeedbackSounds();
    ~FeedbackSounds();
    FeedbackSounds(const FeedbackSounds&) = delete;
    FeedbackSounds& operator=(const FeedbackSounds&) = delete;

    bool available() const { return device_ != 0; }
    const std::string& why() const { return why_; }  // why not available
    // SDL's audio driver ("pulseaudio", "alsa", ...; "dummy" plays nowhere); "" when none opened.
    const std::string& driver() const { return driver_; }
    // Every feedback sound's name, in the order the sound check plays them.
    static const std::vector<std::string>& names();
    // One of names(); anything else is silent. Never blocks.
    void play(const std::string& which);
    // Each of names() in turn with a pause between, so the supervisor can check that all can
    // be heard before a session. Never blocks.
    void playEach();

    // The samples of a sound (mono float at kRate), for tests and for play().
    static constexpr int kRate = 48000;
    static std::vector<float> samples(const std::string& which);

private:
    std::uint32_t device_ = 0;
    std::string why_, driver_;
};

}  // namespace warplab::live
