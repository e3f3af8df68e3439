#include "requirements.hpp"
