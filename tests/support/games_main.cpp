// The main of the test executables that play the built-in games: the games are made known to
// the protocol loader first, as the app does (games/games.h).
#include <gtest/gtest.h>

#include "games/games.h"

int main(int argc, char** argv) {
    warplab::games::registerGames();
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
