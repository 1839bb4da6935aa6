/*
 * link_fixture.h - the ground station the link's tests talk to
 * (link_fixture.c, shared by test_fw_link.c and test_fw_link_gcs.c): the
 * step and its link (setUp: level, at rest, at home with a 3-D fix, a
 * receiver with the mode switch at manual, airspeed 15 m/s), the frames
 * the link sent (rx[0 .. nrx), parsed by the generated parser) and the
 * generated pack helpers to send it frames.
 */
#ifndef HT_LINK_FIXTURE_H
#define HT_LINK_FIXTURE_H

#include "unity.h"

#include "link/fw_link.h"
#include "mavlink/common/mavlink.h" /* the messages, to build and read frames */

#define GCS_SYS  255u
#define GCS_COMP 190u
#define OUR_SYS  1u
#define OUR_COMP 1u
#define HOME_LAT 470000000
#define HOME_LON 80000000
#define MAX_RX   4096u

extern fw_config_t cfg;
extern fw_t fw;
extern fw_link_t lk;
extern fw_inputs_t in;
extern fw_output_t out;
extern uint32_t now_ms;
extern uint32_t samples;
extern uint8_t gps_on; /* 0: no GPS solution reaches the step */
extern mavlink_message_t rx[MAX_RX];
extern unsigned nrx;
extern mavlink_status_t rx_st;
extern const int32_t wp_lat[4], wp_lon[4]; /* a square around home */

/* what the link sent, parsed into rx */
void drain(void);
/* k control steps (40 Hz), the link after each */
void steps(unsigned k);
/* a param_id as the pack functions read it: 16 bytes, zero-padded */
const char *id16(const char *s);
void send(const mavlink_message_t *m);
unsigned count_id(uint32_t id, unsigned from);
/* the last message of an id since from, or NULL */
const mavlink_message_t *last_id(uint32_t id, unsigned from);
/* the last PARAM_VALUE of id since from (fails the test if none) */
float param_value_of(const char *id, unsigned from);
/* PARAM_SET, REAL32 */
void set_param(const char *id, float v);
void send_item(uint16_t seq, int32_t lat, int32_t lon, float z, uint8_t frame, uint16_t command);
void send_count(uint16_t n);
/* the seq of the last MISSION_REQUEST_INT since from, or -1 */
int last_request(unsigned from);
/* the type of the last MISSION_ACK since from, or -1 */
int last_ack(unsigned from);
/* the square, 4 items, accepted */
void upload_square(void);
/* the result of the last COMMAND_ACK since from (of that command), or -1 */
int command_result(unsigned from, uint16_t command);
/* DO_SET_MODE with the custom-mode flag */
void do_set_mode(uint32_t custom);

#endif /* HT_LINK_FIXTURE_H */
