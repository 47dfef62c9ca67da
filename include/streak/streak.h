#pragma once

// streak's public API: analytic motion blur of moving and deforming triangle meshes.
//
//   streak::api::Scene scene = streak::api::Scene::load("builtin:cubes");
//   streak::api::RenderSettings settings;
//   settings.method = "analytic";
//   streak::api::Image image = streak::api::render(scene, settings).image;
//   streak::api::writeImage(image, "cubes.png");
//
// Everything is in linear light; the shutter interval is t in [0, 1]. Every function throws
// streak::Error (one line naming the problem) for bad input and never exits.

#include "streak/blur_shell.h"
#include "streak/error.h"
#include "streak/image.h"
#include "streak/render.h"
#include "streak/scene.h"
