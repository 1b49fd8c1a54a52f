#include "viewport.h"

#include <QCursor>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QWheelEvent>
#include <cmath>

#include "document.h"
#include "plate_match_worker.h"
#include "placement.h"

namespace dp::ui {

Viewport::Viewport(Document* doc, QWidget* parent)
    : QWidget(parent), doc_(doc), pick_(new PickTool(this)), matte_(new MatteTool(this)),
      plate_(new PlateMatchWorker(this)) {
    connect(plate_, &PlateMatchWorker::matched, this,
            [this](std::shared_ptr<const Image> source, std::shared_ptr<const Image> image) {
                matchedSource_ = std::move(source);
                matched_ = std::move(image);
                rebuildImage();
            });
    setFocusPolicy(Qt::StrongFocus);
    setMinimumSize(320, 200);
    setAttribute(Qt::WA_OpaquePaintEvent);
    setToolTip(
        tr("Click an object or a light's glyph to select it; drag to move (G), rotate (R) or scale (S).\n"
           "Wheel zooms, middle button pans, X deletes, Esc cancels a drag."));
    connect(doc_, &Document::changed, this, [this] { update(); });
    connect(pick_, &PickTool::changed, this, [this] { update(); });
    // The brush's outline follows the cursor while the matte tool paints.
    connect(matte_, &MatteTool::changed, this, [this] {
        if (!dragging_) setMouseTracking(matte_->active());
        update();
    });
    connect(doc_, &Document::selectionChanged, this, [this](int index) {
        overlays_.selected = index;
        update();
    });
}

void Viewport::setFrame(std::shared_ptr<const RenderFrame> frame) {
    frame_ = std::move(frame);
    if (!renderSize_.isValid() && frame_ && frame_->photo)
        renderSize_ = QSize(frame_->photo->width(), frame_->photo->height());
    rebuildImage();
}

void Viewport::setDenoise(bool on) {
    denoise_ = on;
    rebuildImage();
}

void Viewport::setDenoised(std::shared_ptr<const RenderFrame> frame, std::shared_ptr<const Image> image) {
    if (!frame || !image) return;
    // An older pass of the same state never replaces a newer one's.
    if (frame->generation == denoisedGeneration_ && frame->update.stats.passes < denoisedPasses_) return;
    if (frame->generation == denoisedGeneration_ && frame->preview && !denoisedPreview_) return;
    denoised_ = std::move(image);
    denoisedGeneration_ = frame->generation;
    denoisedPasses_ = frame->update.stats.passes;
    denoisedPreview_ = frame->preview;
    if (frame_ && frame_->generation == denoisedGeneration_) rebuildImage();
}

void Viewport::setRenderSize(QSize size) {
    renderSize_ = size;
    update();
}

void Viewport::setViewMode(ViewMode mode) {
    mode_ = mode;
    rebuildImage();
}

void Viewport::setExposure(float stops) {
    exposure_ = stops;
    rebuildImage();
}

void Viewport::setView(const ViewSettings& view) {
    if (view.view == view_.view && view.look == view_.look) return;
    view_ = view;
    view_.exposure = 0;
    transform_.reset();
    try {
        if (!(view_.view == "Standard" && view_.look.empty())) transform_ = std::make_shared<const DisplayTransform>(view_);
    } catch (const std::exception&) {
        transform_.reset();  // an unknown view (a project from another machine's config) shows Standard
    }
    rebuildImage();
}

void Viewport::setOverlays(const OverlayOptions& o) {
    overlays_ = o;
    overlays_.selected = doc_->selected();
    update();
}

void Viewport::setOverlaysVisible(bool on) {
    showOverlays_ = on;
    update();
}

void Viewport::setGizmoMode(GizmoMode mode) {
    if (mode == gizmo_) return;
    gizmo_ = mode;
    Q_EMIT gizmoModeChanged(mode);
}

void Viewport::fitView() {
    zoom_ = 1;
    pan_ = QPointF();
    update();
}

void Viewport::rebuildImage() {
    showingDenoised_ = false;
    if (!frame_) {
        shown_ = QImage();
    } else if (mode_ == ViewMode::Photo && frame_->photo) {
        shown_ = to_display(*frame_->photo, exposure_, kDisplayMaxWidth, transform_.get());
    } else if (mode_ == ViewMode::Delta) {
        shown_ = to_false_colour(frame_->dL(), exposure_, kDisplayMaxWidth);
    } else {
        // Denoised: a refined frame shows the denoised picture of its state, however many
        // passes behind (laid over the refined picture as the frame is); drag frames stay raw.
        const Image* image = &frame_->image();
        if (denoise_ && !frame_->drag && denoised_ &&
            denoisedGeneration_ == frame_->generation && (!denoisedPreview_ || frame_->preview) &&
            denoised_->width() == frame_->image().width()) {
            image = denoised_.get();
            showingDenoised_ = true;
        }
        // Matched to the plate: refined pictures only (a drag's or a quick pass's stay raw).
        showingMatched_ = false;
        if (matchPlate_ && !frame_->drag && !frame_->preview && !frame_->composited()) {
            const std::shared_ptr<const Image> source =
                showingDenoised_ ? denoised_ : std::shared_ptr<const Image>(frame_, &frame_->update.image);
            if (matched_ && matchedSource_ == source) {
                image = matched_.get();
                showingMatched_ = true;
            } else if (requested_.lock() != source) {
                requested_ = source;
                plate_->request(frame_, source);
            }
        }
        shown_ = to_display(*image, exposure_, kDisplayMaxWidth, transform_.get());
    }
    update();
}

void Viewport::setMatchPlate(bool on) {
    if (matchPlate_ == on) return;
    matchPlate_ = on;
    rebuildImage();
}

QString Viewport::plateSummary() const {
    return plate_->summary();
}

QTransform Viewport::imageToWidget() const {
    const QSize s = renderSize_.isValid() ? renderSize_ : QSize(16, 9);
    const double fit = std::min(width() / double(s.width()), height() / double(s.height()));
    const double k = fit * zoom_;
    QTransform t;
    t.translate(width() / 2.0 + pan_.x(), height() / 2.0 + pan_.y());
    t.scale(k, k);
    t.translate(-s.width() / 2.0, -s.height() / 2.0);
    return t;
}

QRectF Viewport::imageRect() const {
    const QSize s = renderSize_.isValid() ? renderSize_ : QSize(16, 9);
    return imageToWidget().mapRect(QRectF(0, 0, s.width(), s.height()));
}

QPointF Viewport::widgetFromRender(QPointF px) const {
    return imageToWidget().map(px + QPointF(0.5, 0.5));
}

vec2 Viewport::toImage(QPointF widget) const {
    const QPointF p = imageToWidget().inverted().map(widget);
    return vec2(float(p.x() - 0.5), float(p.y() - 0.5));  // pixel centres at integers
}

Camera Viewport::camera() const {
    const int pw = frame_ && frame_->photo ? frame_->photo->width() : renderSize_.width();
    const int ph = frame_ && frame_->photo ? frame_->photo->height() : renderSize_.height();
    return view_camera(doc_->project(), pw, ph, renderSize_.width(), renderSize_.height());
}

bool Viewport::widgetPosition(const vec3& world, QPointF& out) const {
    if (!renderSize_.isValid()) return false;
    vec2 px;
    if (!camera().project(world, px)) return false;
    out = imageToWidget().map(QPointF(px.x + 0.5, px.y + 0.5));
    return true;
}

void Viewport::paintEvent(QPaintEvent*) {
    QPainter p(this);
    p.fillRect(rect(), QColor(38, 38, 40));
    if (!doc_->isOpen() || !renderSize_.isValid()) {
        p.setPen(QColor(190, 190, 190));
        p.drawText(rect(), Qt::AlignCenter,
                   tr("Open a project, or drop a photograph and a light probe here."));
        return;
    }
    const QTransform t = imageToWidget();
    if (!shown_.isNull()) {
        p.save();
        p.setTransform(t);
        p.setRenderHint(QPainter::SmoothPixmapTransform, zoom_ < 2.0);
        p.drawImage(QRectF(0, 0, renderSize_.width(), renderSize_.height()), shown_);
        p.restore();
    }
    const QTransform camToWidget = QTransform::fromTranslate(0.5, 0.5) * t;
    if (overlaysDrawn()) {
        OverlayOptions o = overlays_;
        o.selected = doc_->selected();
        o.selectedLight = doc_->selectedLight();
        p.setClipRect(imageRect());  // overlays belong to the photo, not the margin around it
        draw_overlays(p, doc_->project(), camera(), camToWidget, o);
        p.setClipping(false);
    }
    p.setClipRect(imageRect());
    matte_->paint(p, camToWidget);
    p.setClipping(false);
    pick_->paint(p, camToWidget);
    if (modal_) {
        // What the keys have set so far, as Blender shows it in its header.
        static const char* verbs[] = {"Move", "Rotate", "Scale"};
        QString text = tr(verbs[int(gizmo_)]);
        if (axis_ >= 0) text += tr(" along %1").arg(QChar('X' + axis_));
        if (!typed_.isEmpty()) text += QStringLiteral(": %1|").arg(typed_);
        text += tr("   (X Y Z: axis; digits: value; Enter confirms, Esc cancels)");
        const QRectF box(10, 10, std::min(width() - 20, 560), 26);
        p.fillRect(box, QColor(0, 0, 0, 170));
        p.setPen(QColor(255, 230, 120));
        p.drawText(box.adjusted(8, 0, -8, 0), Qt::AlignVCenter | Qt::AlignLeft, text);
    }
}

bool Viewport::hasSelection() const {
    return doc_->selected() >= 0 || doc_->selectedLight() >= 0;
}

Transform& Viewport::selectionTransform(Project& p) const {
    if (doc_->selectedLight() >= 0) return p.lights[size_t(doc_->selectedLight())].transform;
    return p.objects[size_t(doc_->selected())].transform;
}

void Viewport::beginDrag(QPointF pos) {
    if (!hasSelection()) return;
    dragging_ = true;
    pressPos_ = lastPos_ = pos;
    projectAtDrag_ = doc_->project();
    dragStart_ = selectionTransform(projectAtDrag_);
    dragKey_ = doc_->newMergeKey();
    axis_ = -1;
    typed_.clear();
    Q_EMIT dragStarted();
}

bool Viewport::startModalTransform(GizmoMode mode) {
    if (dragging_ || pick_->active() || !hasSelection() || !renderSize_.isValid()) return false;
    QPointF at = mapFromGlobal(QCursor::pos());
    if (!rect().contains(at.toPoint())) {
        // The key was pressed with the mouse over a panel: start from the object itself.
        Project p = doc_->project();
        if (!widgetPosition(selectionTransform(p).translation, at))
            at = QPointF(rect().center());
        QCursor::setPos(mapToGlobal(at.toPoint()));
    }
    modeBeforeModal_ = gizmo_;
    modal_ = true;
    setGizmoMode(mode);
    setFocus();  // Enter and Esc end it, whichever field had the focus
    setMouseTracking(true);
    grabMouse();  // the object follows the mouse over the panels too
    beginDrag(at);
    return true;
}

void Viewport::finishDrag(bool cancel) {
    if (!dragging_) return;
    dragging_ = false;
    axis_ = -1;
    typed_.clear();
    setMouseTracking(matte_->active());
    if (cancel) doc_->edit(tr("Cancel transform"), projectAtDrag_, dragKey_);
    if (modal_) {
        modal_ = false;
        releaseMouse();
        setGizmoMode(modeBeforeModal_);
    }
    Q_EMIT dragFinished();
}

void Viewport::mousePressEvent(QMouseEvent* e) {
    setFocus();
    if (e->button() == Qt::MiddleButton) {
        panning_ = true;
        lastPos_ = e->position();
        return;
    }
    if (dragging_) {  // a modal G/R/S drag: left confirms, right cancels
        finishDrag(e->button() != Qt::LeftButton);
        return;
    }
    if (e->button() != Qt::LeftButton || !renderSize_.isValid()) return;
    const vec2 px = toImage(e->position());
    if (matte_->press(QPointF(px.x, px.y), e->modifiers())) return;
    if (pick_->press(QPointF(px.x, px.y))) return;
    // A light's glyph is small and drawn over what is behind it: it is picked first.
    const float perPixel = float(imageToWidget().m11());
    const int light = pick_light(doc_->project(), camera(), px.x, px.y, 12.0f / std::max(perPixel, 1e-3f));
    if (light >= 0) {
        doc_->selectLight(light);
        beginDrag(e->position());
        return;
    }
    const int hit = pick_object(doc_->project(), camera(), px.x, px.y);
    doc_->select(hit);
    if (hit >= 0) beginDrag(e->position());
}

void Viewport::mouseMoveEvent(QMouseEvent* e) {
    if (panning_) {
        pan_ += e->position() - lastPos_;
        lastPos_ = e->position();
        update();
        return;
    }
    if (matte_->active()) {
        const vec2 px = toImage(e->position());
        matte_->move(QPointF(px.x, px.y));
        return;
    }
    if (pick_->active()) {
        const vec2 px = toImage(e->position());
        pick_->move(QPointF(px.x, px.y));
        return;
    }
    if (!dragging_ || !hasSelection()) return;
    lastPos_ = e->position();
    if (typed_.isEmpty()) applyDrag();  // a typed value holds until it is erased
}

void Viewport::applyDrag() {
    if (!dragging_ || !hasSelection()) return;
    bool typed = false;
    const float value = typed_.toFloat(&typed);
    static const char* verbs[] = {"Move", "Rotate", "Scale"};
    if (const int light = doc_->selectedLight(); light >= 0) {
        Project p = projectAtDrag_;
        VirtualLight& l = p.lights[size_t(light)];
        if (typed && std::isfinite(value) && !(gizmo_ == GizmoMode::Scale && value <= 0))
            l.transform = typed_transform(gizmo_, dragStart_, axis_, value);
        else
            l.transform = light_drag_transform(gizmo_, dragStart_, camera(), toImage(pressPos_),
                                               toImage(lastPos_), axis_);
        doc_->edit(tr("%1 %2").arg(tr(verbs[int(gizmo_)]), QString::fromStdString(l.name)), p, dragKey_);
        update();
        return;
    }
    const int sel = doc_->selected();
    Project p = projectAtDrag_;
    VirtualObject& obj = p.objects[size_t(sel)];
    if (typed && std::isfinite(value) && !(gizmo_ == GizmoMode::Scale && value <= 0))
        obj.transform = typed_transform(gizmo_, dragStart_, axis_, value);
    else
        obj.transform = axis_drag_transform(gizmo_, dragStart_, camera(), toImage(pressPos_),
                                            toImage(lastPos_), axis_, &projectAtDrag_);
    // Scaling keeps the lowest point where it was: an object on the floor stays on it.
    if (gizmo_ == GizmoMode::Scale)
        obj.transform =
            kept_on_base(projectAtDrag_, projectAtDrag_.objects[size_t(sel)], obj.transform);
    doc_->edit(tr("%1 %2").arg(tr(verbs[int(gizmo_)]), QString::fromStdString(obj.name)), p,
               dragKey_);
    update();
}

bool Viewport::modalKey(QKeyEvent* e) {
    if (!modal_ || (e->modifiers() & ~(Qt::ShiftModifier | Qt::KeypadModifier))) return false;
    const int key = e->key();
    if (key == Qt::Key_X || key == Qt::Key_Y || key == Qt::Key_Z) {
        const int axis = key - Qt::Key_X;
        axis_ = axis_ == axis ? -1 : axis;  // the same axis again frees it
    } else if ((key >= Qt::Key_0 && key <= Qt::Key_9) || key == Qt::Key_Period ||
               key == Qt::Key_Comma) {
        typed_ += key == Qt::Key_Comma ? QChar('.') : QChar(key);
    } else if (key == Qt::Key_Minus) {
        // As in Blender: minus negates what is typed, wherever the cursor is.
        typed_ = typed_.startsWith('-') ? typed_.mid(1) : QStringLiteral("-") + typed_;
    } else if (key == Qt::Key_Backspace) {
        typed_.chop(1);
    } else {
        return false;
    }
    applyDrag();
    return true;
}

bool Viewport::event(QEvent* e) {
    // During a modal transform X, Y, Z and the digits belong to it, not to the window's
    // shortcuts (X would delete the object).
    if (e->type() == QEvent::ShortcutOverride && modal_) {
        auto* k = static_cast<QKeyEvent*>(e);
        const int key = k->key();
        if (key == Qt::Key_X || key == Qt::Key_Y || key == Qt::Key_Z ||
            (key >= Qt::Key_0 && key <= Qt::Key_9) || key == Qt::Key_Period ||
            key == Qt::Key_Comma || key == Qt::Key_Minus || key == Qt::Key_Backspace) {
            e->accept();
            return true;
        }
    }
    return QWidget::event(e);
}

void Viewport::mouseReleaseEvent(QMouseEvent* e) {
    if (e->button() == Qt::MiddleButton) {
        panning_ = false;
        return;
    }
    if (e->button() == Qt::LeftButton && matte_->active()) {
        const vec2 px = toImage(e->position());
        matte_->release(QPointF(px.x, px.y));
        return;
    }
    if (e->button() == Qt::LeftButton && pick_->active()) {
        const vec2 px = toImage(e->position());
        pick_->release(QPointF(px.x, px.y));
        return;
    }
    if (e->button() == Qt::LeftButton && dragging_ && !modal_) finishDrag(false);
}

void Viewport::mouseDoubleClickEvent(QMouseEvent* e) {
    if (e->button() == Qt::LeftButton && matte_->active() && renderSize_.isValid()) {
        const vec2 px = toImage(e->position());
        if (matte_->doubleClick(QPointF(px.x, px.y))) return;
    }
    QWidget::mouseDoubleClickEvent(e);
}

void Viewport::wheelEvent(QWheelEvent* e) {
    const QPointF cursor = e->position();
    const QPointF before = imageToWidget().inverted().map(cursor);
    zoom_ = std::clamp(zoom_ * std::pow(1.15, e->angleDelta().y() / 120.0), 0.1, 32.0);
    const QPointF after = imageToWidget().map(before);
    pan_ += cursor - after;  // keeps the image point under the cursor
    update();
}

void Viewport::keyPressEvent(QKeyEvent* e) {
    // G, R, S and X are the window's actions (they work from any panel); here only what ends a
    // drag or a pick, and a modal transform's axes and typed value.
    if (modalKey(e)) return;
    if (matte_->key(e->key())) return;
    switch (e->key()) {
        case Qt::Key_Return:
        case Qt::Key_Enter:
            if (modal_) finishDrag(false);
            return;
        case Qt::Key_Escape:
            if (pick_->active()) pick_->cancel();
            finishDrag(true);
            return;
        case Qt::Key_Home:
            fitView();
            return;
        default:
            QWidget::keyPressEvent(e);
    }
}

}  // namespace dp::ui
