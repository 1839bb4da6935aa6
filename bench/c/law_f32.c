/* law_f32.c - the single-precision law (bench only; see law_impl.h). */
#include <math.h>

#include "law_real.h"

#define LAW_REAL   float
#define LAW_SQRT   sqrtf
#define LAW_SUFFIX f32
#define LAW_PARAMS law_params_f32_t
#define LAW_INPUT  law_input_f32_t
#define LAW_OUTPUT law_output_f32_t
#include "law_impl.h"
