// The JSON spellings of the adaptive procedures' choices, once: the parser, the messages that
// list the allowed values, the canonical copy and the export all read them.
#pragma once

#include "adaptive/block.h"
#include "adaptive/psychometric.h"
#include "protocol/study_protocol.h"

namespace warplab::protocol {

template <>
struct EnumNames<adaptive::Method> {
    static constexpr EnumName<adaptive::Method> list[] = {{adaptive::Method::QuestPlus, "quest_plus"},
                                                          {adaptive::Method::Staircase, "staircase"},
                                                          {adaptive::Method::ConstantStimuli, "constant_stimuli"}};
};
template <>
struct EnumNames<adaptive::Shape> {
    static constexpr EnumName<adaptive::Shape> list[] = {{adaptive::Shape::Weibull, "weibull"},
                                                         {adaptive::Shape::Logistic, "logistic"}};
};
template <>
struct EnumNames<adaptive::Scale> {
    static constexpr EnumName<adaptive::Scale> list[] = {{adaptive::Scale::Log, "log"},
                                                         {adaptive::Scale::Linear, "linear"}};
};

}  // namespace warplab::protocol
