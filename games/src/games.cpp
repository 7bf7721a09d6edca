#include "games/games.h"

#include <mutex>

#include "click/click_study.h"
#include "discrimination/discrimination_study.h"
#include "game/registry.h"
#include "shooter/shooter_study.h"

namespace warplab::games {

void registerGames() {
    static std::once_flag once;
    std::call_once(once, [] {
        // The one list of built-in games, in the order gameNames() gives them.
        game::registerGame("shooter", game::parseShooterStudy, game::shooterExport());
        game::registerGame("click", game::parseClickStudy, game::clickExport());
        game::registerGame("discrimination", discrimination::parseDiscriminationStudy,
                           discrimination::discriminationExport());
    });
}

}  // namespace warplab::games
