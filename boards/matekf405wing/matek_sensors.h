/*
 * matek_sensors.h - the Matek F405-WING's sensors (matek_sensors.c, which
 * also implements board_sensors_read): IMU (SPI1 + EXTI4), baro (I2C1),
 * pitot (I2C2), GPS (USART3).
 */
#ifndef HT_MATEK_SENSORS_H
#define HT_MATEK_SENSORS_H

#include <stdint.h>

void matek_sensors_init(void);
/* Every wake of the tick loop: the IMU sample on data-ready (1 kHz). */
void matek_sensors_poll(void);
uint32_t matek_sensors_imu_samples(void);

#endif /* HT_MATEK_SENSORS_H */
