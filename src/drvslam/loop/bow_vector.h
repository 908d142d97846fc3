// The bag-of-words types, under the name loop/ code has always used; they are defined in map/
// (map/bow_vector.h) so that frames and keyframes, which come earlier in the module order, can
// hold them.
#pragma once

#include "drvslam/map/bow_vector.h"
