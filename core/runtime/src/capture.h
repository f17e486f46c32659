/* capture.c: a frame's barriers and dispatches kept as data, for a replay. */
#ifndef VRG_CAPTURE_H
#define VRG_CAPTURE_H

#include "internal.h"

/* An empty capture, which vrg_graph_capture_frame sets as
 * g->capture for one frame; the recorder's barrier and dispatch calls add
 * to it while it is set */
vrg_capture *_vrg_capture_new(PFN_vkCmdPushDescriptorSetKHR push_descriptor);
void _vrg_capture_barrier(struct vrg_capture *c, const VkDependencyInfo *dep);
void _vrg_capture_dispatch(struct vrg_capture *c, VkPipeline pipeline, VkPipelineLayout layout, uint32_t write_count,
                          const VkWriteDescriptorSet *writes, const void *push, uint32_t push_size, const uint32_t groups[3]);
#endif
