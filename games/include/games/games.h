// The built-in games made known to the protocol loader (game/registry.h). The app calls it
// before it reads any protocol, as do the tests that play the games; calling it again does
// nothing.
#pragma once

namespace warplab::games {

void registerGames();

}  // namespace warplab::games
