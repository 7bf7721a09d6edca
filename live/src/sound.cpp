#include "sound.h"

#include <SDL.h>

#if defined(__linux__)
#include <dlfcn.h>
#endif

#include <algorithm>
#include <cmath>

namespace warplab::live {
namespace {

// A tone gliding from f0 to f1 Hz with a 5 ms fade in and out (no clicks).
void tone(std::vector<float>& out, double f0, double f1, double seconds, double gain) {
    const int n = static_cast<int>(seconds * FeedbackSounds::kRate);
    const int fade = FeedbackSounds::kRate / 200;
    double phase = 0.0;
    for (int i = 0; i < n; ++i) {
        const double f = f0 + (f1 - f0) * i / n;
        phase += 2.0 * 3.14159265358979323846 * f / FeedbackSounds::kRate;
        const double envelope = std::min({1.0, static_cast<double>(i) / fade, static_cast<double>(n - i) / fade});
        out.push_back(static_cast<float>(gain * envelope * std::sin(phase)));
    }
}

#if defined(__linux__)
void ignoreAlsaError(const char*, int, const char*, int, const char*, ...) {}
#endif

// ALSA's library prints each error of its configuration on stderr ("ALSA lib confmisc.c:855:
// (parse_card) cannot find card '0'": eight lines on a machine without a sound card) before SDL
// gives up with one error of its own, which the run says once, as a note. ALSA's documented
// way to route them is snd_lib_error_set_handler; SDL loads libasound at run time, so it is
// set on the same library, loaded the same way: nothing to link, nothing done where there is
// no ALSA. Errors that reach SDL still reach the note.
void quietAlsaErrors() {
#if defined(__linux__)
    static void* const alsa = dlopen("libasound.so.2", RTLD_NOW | RTLD_GLOBAL);  // kept loaded: it holds the handler
    if (alsa == nullptr) return;
    using Handler = void (*)(const char*, int, const char*, int, const char*, ...);
    using SetHandler = int (*)(Handler);
    if (const auto set = reinterpret_cast<SetHandler>(dlsym(alsa, "snd_lib_error_set_handler"))) set(&ignoreAlsaError);
#endif
}

}  // namespace

std::vector<float> FeedbackSounds::samples(const std::string& which) {
    std::vector<float> out;
    if (which == "hit") {  // bright, rising: two quick notes
        tone(out, 880, 880, 0.07, 0.4);
        tone(out, 1320, 1320, 0.10, 0.4);
    } else if (which == "miss") {  // low, falling
        tone(out, 330, 220, 0.20, 0.45);
    } else if (which == "timeout") {  // a low double buzz
        tone(out, 180, 180, 0.12, 0.45);
        tone(out, 0, 0, 0.05, 0.0);
        tone(out, 180, 180, 0.12, 0.45);
    }
    return out;
}

const std::vector<std::string>& FeedbackSounds::names() {
    static const std::vector<std::string> list{"hit", "miss", "timeout"};
    return list;
}

FeedbackSounds::FeedbackSounds() {
    quietAlsaErrors();
    if (SDL_InitSubSystem(SDL_INIT_AUDIO) != 0) {
        why_ = std::string("no audio: ") + SDL_GetError();
        return;
    }
    SDL_AudioSpec want{};
    want.freq = kRate;
    want.format = AUDIO_F32SYS;
    want.channels = 1;
    want.samples = 512;  // ~10 ms: the sound starts within a frame or two of the click
    device_ = SDL_OpenAudioDevice(nullptr, 0, &want, nullptr, 0);
    if (device_ == 0) {
        why_ = std::string("no audio device: ") + SDL_GetError();
        SDL_QuitSubSystem(SDL_INIT_AUDIO);
        return;
    }
    if (const char* driver = SDL_GetCurrentAudioDriver()) driver_ = driver;
    SDL_PauseAudioDevice(device_, 0);
}

FeedbackSounds::~FeedbackSounds() {
    if (device_ != 0) {
        SDL_CloseAudioDevice(device_);
        SDL_QuitSubSystem(SDL_INIT_AUDIO);
    }
}

void FeedbackSounds::play(const std::string& which) {
    if (device_ == 0) return;
    const auto s = samples(which);
    if (s.empty()) return;
    SDL_ClearQueuedAudio(device_);  // a new outcome cuts the last one short
    SDL_QueueAudio(device_, s.data(), static_cast<Uint32>(s.size() * sizeof(float)));
}

}  // namespace warplab::live

namespace warplab::live {

void FeedbackSounds::playEach() {
    if (device_ == 0) return;
    std::vector<float> all;
    for (const std::string& name : names()) {
        const auto s = samples(name);
        all.insert(all.end(), s.begin(), s.end());
        all.insert(all.end(), kRate / 2, 0.0f);  // half a second apart: three sounds, not one
    }
    SDL_ClearQueuedAudio(device_);
    SDL_QueueAudio(device_, all.data(), static_cast<Uint32>(all.size() * sizeof(float)));
}

}  // namespace warplab::live
