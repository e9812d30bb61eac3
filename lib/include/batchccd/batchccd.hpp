#pragma once

// The whole public API of batchccd.
#include "batchccd/batch.hpp"
#include "batchccd/ccd.hpp"
#include "batchccd/io.hpp"
#include "batchccd/options.hpp"
#include "batchccd/query.hpp"
#include "batchccd/version.hpp"
