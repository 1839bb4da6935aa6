/* law_f64.c - the double-precision law (bench only; see law_impl.h). */
#include <math.h>

#include "law_real.h"

#define LAW_REAL   double
#define LAW_SQRT   sqrt
#define LAW_SUFFIX f64
#define LAW_PARAMS law_params_f64_t
#define LAW_INPUT  law_input_f64_t
#define LAW_OUTPUT law_output_f64_t
#include "law_impl.h"
