#include "render/textures.h"

namespace engine {

}  // namespace engine
