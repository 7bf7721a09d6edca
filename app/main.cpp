#include "app/app.h"

int main(int argc, char** argv) {
    return warplab::app::run(std::vector<std::string>(argv + 1, argv + argc));
}
