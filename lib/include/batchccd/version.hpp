#pragma once

// Semantic version of the public API.
#define BATCHCCD_VERSION_MAJOR 0
#define BATCHCCD_VERSION_MINOR 1
#define BATCHCCD_VERSION_PATCH 0
#define BATCHCCD_VERSION "0.1.0"
