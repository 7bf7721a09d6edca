// The study window: SDL2 with a GL 4.1 core context and vsync.
#include <SDL.h>

#include "renderer/context_backends.h"

namespace warplab::renderer {
namespace {

void* loadProc(const char* name) { return SDL_GL_GetProcAddress(name); }

class WindowContext final : public GlContext {
public:
    explicit WindowContext(const ContextOptions& options) {
        if (SDL_InitSubSystem(SDL_INIT_VIDEO) != 0)
            throw ContextError(std::string("cannot open a window: ") + SDL_GetError());
        videoInitialised_ = true;
        SDL_GL_SetAttribute(SDL_GL_CONTEXT_MAJOR_VERSION, 4);
        SDL_GL_SetAttribute(SDL_GL_CONTEXT_MINOR_VERSION, 1);
        SDL_GL_SetAttribute(SDL_GL_CONTEXT_PROFILE_MASK, SDL_GL_CONTEXT_PROFILE_CORE);
        SDL_GL_SetAttribute(SDL_GL_CONTEXT_FLAGS, SDL_GL_CONTEXT_FORWARD_COMPATIBLE_FLAG);
        SDL_GL_SetAttribute(SDL_GL_DOUBLEBUFFER, 1);
        SDL_GL_SetAttribute(SDL_GL_DEPTH_SIZE, 0);  // the renderer has its own depth buffers
        Uint32 flags = SDL_WINDOW_OPENGL | (options.visible ? SDL_WINDOW_SHOWN : SDL_WINDOW_HIDDEN);
        window_ = SDL_CreateWindow(options.title.c_str(), SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED,
                                   options.width, options.height, flags);
        if (window_ == nullptr) throw ContextError(std::string("cannot open a window: ") + SDL_GetError());
        context_ = SDL_GL_CreateContext(window_);
        if (context_ == nullptr)
            throw ContextError(std::string("the window system offers no OpenGL 4.1 core context: ") + SDL_GetError());
        // Adaptive vsync is not what a study wants (it tears); plain vsync or, if refused, none,
        // which the frame log will show as measured frame times.
        SDL_GL_SetSwapInterval(options.vsync ? 1 : 0);
        initialise(&loadProc, "window");
    }

    ~WindowContext() override {
        if (context_ != nullptr) SDL_GL_DeleteContext(context_);
        if (window_ != nullptr) SDL_DestroyWindow(window_);
        if (videoInitialised_) SDL_QuitSubSystem(SDL_INIT_VIDEO);
    }

    bool hasWindow() const override { return true; }
    void swapBuffers() override { SDL_GL_SwapWindow(window_); }
    bool pumpEvents() override {
        SDL_Event event;
        bool open = true;
        while (SDL_PollEvent(&event))
            if (event.type == SDL_QUIT) open = false;
        return open;
    }
    int drawableWidth() const override {
        int w = 0, h = 0;
        SDL_GL_GetDrawableSize(window_, &w, &h);
        return w;
    }
    int drawableHeight() const override {
        int w = 0, h = 0;
        SDL_GL_GetDrawableSize(window_, &w, &h);
        return h;
    }

private:
    bool videoInitialised_ = false;
    SDL_Window* window_ = nullptr;
    SDL_GLContext context_ = nullptr;
};

}  // namespace

std::unique_ptr<GlContext> createWindowContext(const ContextOptions& options) {
    return std::make_unique<WindowContext>(options);
}

}  // namespace warplab::renderer
