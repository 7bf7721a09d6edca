// For every game's protocol parser (protocol/fields.h): a list of questions (protocol/questions.h) as every game's protocol
// writes it. One reader and one writer, so that a question reads, is checked and is written
// the same in every game's file (docs/protocol.md, "Questions").
#pragma once

#include <string>
#include <vector>

#include "protocol/fields.h"
#include "protocol/questions.h"

namespace warplab::protocol::fields {

// A question's keys, in the order they are read and written.
std::vector<const char*> questionKeyNames();

// The array `key` of `parent` (at `path`) as a list of questions; absent leaves `out` as it is,
// and [] asks nothing.
void readQuestions(const Reader& r, const Json* parent, const std::string& path, const char* key,
                   std::vector<Question>& out);
// The canonical form: each question with every key of its kind, and only those, in table order.
Json questionsJson(const std::vector<Question>& questions);

// A section's "questions" key, new in format_version `since`: older files may not have it, and
// a struct of an older version is written with it only where it is not the default (so that
// parsing the copy refuses it rather than asking something else).
template <class P, class Get>
Key<P> questionsKey(Get get, int since) {
    Key<P> k{"questions",
             [get](const Reader& r, const Json* o, const std::string& path, P& p) {
                 readQuestions(r, o, path, "questions", get(p));
             },
             [get](Json& o, const P& p) { o["questions"] = questionsJson(get(p)); },
             [get](const P& p) {
                 const P defaults{};
                 return get(p) == get(defaults);
             }};
    return k.since(since, true);
}

}  // namespace warplab::protocol::fields
